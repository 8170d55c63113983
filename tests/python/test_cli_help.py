"""The CLI's help names every study method the scene format accepts (they drifted: the help
listed six of eight, without ak_mcs and ak_is)."""

import subprocess
import sys

from clearsim.scene.study import METHODS


def test_reliability_help_lists_every_study_method():
    out = subprocess.run([sys.executable, "-m", "clearsim", "reliability", "--help"], capture_output=True, text=True, check=True).stdout
    listed = " ".join(out.split()).replace(" ", "")
    for method in METHODS:
        assert method in listed, method
    assert "series" in out
