"""Model files in and out, results export."""
