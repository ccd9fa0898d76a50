"""The research studies: each module regenerates the tables (and figures) of one study, its page under
docs/results/ or its files in study-results/ (not tracked), by the command at the top of its docstring
(``python -m compare.studies.NAME``). They are run from a checkout and are not installed with the package
(pyproject.toml excludes them); CI runs each one's smoke size (.ci/run)."""
