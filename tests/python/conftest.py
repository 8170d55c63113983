import os

os.environ.setdefault("MPLBACKEND", "Agg")


def pytest_configure(config):
    # No shipped model, scene or documented example may look implausible: a PlausibilityWarning
    # (a unit slip, docs: issue 28 item 6) fails the test that meets it, unless the test expects
    # it (pytest.warns) or filters it (property tests draw implausible numbers on purpose).
    config.addinivalue_line("filterwarnings", "error::clearsim.errors.PlausibilityWarning")
