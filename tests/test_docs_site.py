"""The documentation site (docs/site/) builds in both languages with warnings as errors: a
broken link, a broken docstring or a figure whose code no longer runs fails this test."""
import os
import subprocess
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]
SITE = ROOT / "docs" / "site"


@pytest.mark.parametrize("language", ["en", "pt"])
def test_site_builds(language, tmp_path):
    env = dict(os.environ)
    env.pop("KINELAB_KERNEL", None)          # the site's own choice (see docs/site/conf.py)
    out = tmp_path / language
    run = subprocess.run([sys.executable, "-m", "sphinx", "-W", "--keep-going", "-q",
                          "-c", str(SITE), "-D", f"language={language}", str(SITE / language),
                          str(out)], cwd=ROOT, env=env, capture_output=True, text=True)
    assert run.returncode == 0, run.stderr
    for page in ("index.html", "errata.html", "guides.html"):
        assert (out / page).is_file(), page
    assert f'lang="{language}"' in (out / "index.html").read_text(encoding="utf-8")
    if language == "en":
        assert (out / "api" / "kinelab.kinematics.html").is_file()
