"""The installed package version, for trace metadata."""
from importlib import metadata


def package_version() -> str:
    try:
        return metadata.version("frictionnoise")
    except metadata.PackageNotFoundError:  # running from a source tree without install
        return "0+unknown"
