"""The exceptions of eom (raised by the native module with the Rust messages)."""

from __future__ import annotations


class EomError(ValueError):
    """An error of eom: an unknown model or parameter, a value a model cannot take, a
    reduction that fails at a point. The message is eom's own."""


class ModelFileError(EomError):
    """An invalid model file: ``file``, ``line`` and ``column`` (1-based; 0 for the file as a
    whole) say where."""

    def __init__(self, message: str, file: str = "", line: int = 0, column: int = 0):
        super().__init__(message)
        self.file = file
        self.line = line
        self.column = column
