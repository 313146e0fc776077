"""The ``inherit-sg`` command line: a thin face over the library facade."""
