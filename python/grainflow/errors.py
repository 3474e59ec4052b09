"""The errors grainflow raises: the same two kinds as the command line's exit statuses 2 and 1."""


class InputError(ValueError):
    """A case, key or value refused before anything ran (the command line's exit status 2).

    ``file``, ``key`` and ``reason`` say where and why; ``key`` is the dotted name
    (``"contact.friction"``) or ``""`` when the problem is not one key's.
    """

    def __init__(self, message, file="", key="", reason=""):
        super().__init__(message)
        self.file = file
        self.key = key
        self.reason = reason


class RunError(RuntimeError):
    """A run that failed while running (exit status 1): its outputs, with the error in
    ``summary.json``'s ``errors``, are written."""
