"""The installed package version, for trace metadata (defined once, in :mod:`frictionnoise`)."""
from frictionnoise.base import package_version

__all__ = ["package_version"]
