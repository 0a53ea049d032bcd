"""Registers the ``regression`` marker (run only the tier: ``pytest -m regression``)."""


def pytest_configure(config):
    config.addinivalue_line("markers", "regression: small studies compared with committed golden tables")
