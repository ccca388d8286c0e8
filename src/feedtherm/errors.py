"""Errors that reach the user as one line (the CLI prints them without a traceback)."""


class FeedthermError(Exception):
    """Base of the errors feedtherm reports to its user as one line."""


class DescriptionError(FeedthermError):
    """A system description (or another input file) is missing, unreadable or invalid."""


class ModelError(FeedthermError):
    """A valid description asks for something the models cannot do."""


class Terminated(KeyboardInterrupt):
    """SIGTERM, raised where the program is (the CLI's handler), so that it stops as cleanly as on
    Ctrl-C and says it was terminated; a batch that re-raises an interruption keeps this kind."""
