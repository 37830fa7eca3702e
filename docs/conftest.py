# The site's Sphinx configuration is no test module, and the built site holds no pages to test
# (its Markdown sources are tested where they are, in docs/ and docs/site/).
collect_ignore = ["site/conf.py"]
collect_ignore_glob = ["_build/*"]
