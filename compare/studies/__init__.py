"""Report studies: each module defines ``STUDY = Study(key, label, run)`` (see :mod:`compare.study`)."""
