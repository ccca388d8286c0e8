"""Errors that reach the user as one line (the CLI prints them without a traceback)."""


class FeedthermError(Exception):
    """Base of the errors feedtherm reports to its user as one line."""


class DescriptionError(FeedthermError):
    """A system description (or another input file) is missing, unreadable or invalid."""


class ModelError(FeedthermError):
    """A valid description asks for something the models cannot do."""


class ArgumentError(FeedthermError, ValueError):
    """An argument of the Python API (or the option of the same name on the command line) has a
    value it cannot take.

    The message names the argument as the caller wrote it: ``condition: no condition 'nope' …``
    from :func:`feedtherm.simulate`, ``--condition: no condition 'nope' …`` from the CLI, which
    renders it with :meth:`as_option`.  A ``ValueError`` too, so that callers who catch the
    built-in kind for a bad value catch this one.

    Parameters
    ----------
    argument : str
        The keyword argument's name (``sample_interval``); the CLI's option is the same name with
        dashes (``--sample-interval``).
    detail : str
        What is wrong with its value, one line.
    """

    def __init__(self, argument: str, detail: str):
        # Both in args: the exception pickles (a batch's worker process raises it) and rebuilds as is.
        super().__init__(argument, detail)
        self.argument = argument
        self.detail = detail

    def __str__(self) -> str:
        return f"{self.argument}: {self.detail}"

    @property
    def option(self) -> str:
        """The command line's name of the argument, ``--sample-interval`` for ``sample_interval``."""
        return "--" + self.argument.replace("_", "-")

    def as_option(self) -> str:
        """The message as the command line says it: ``--sample-interval: …``."""
        return f"{self.option}: {self.detail}"


def cli_message(exc: FeedthermError) -> str:
    """What the command line prints after ``feedtherm: error:`` for ``exc``: an argument's error
    names its option (:meth:`ArgumentError.as_option`), every other error says its own message."""
    return exc.as_option() if isinstance(exc, ArgumentError) else str(exc)


class Terminated(KeyboardInterrupt):
    """SIGTERM, raised where the program is (the CLI's handler), so that it stops as cleanly as on
    Ctrl-C and says it was terminated; a batch that re-raises an interruption keeps this kind."""
