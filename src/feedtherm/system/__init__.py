"""What a feed system is and how it runs: the typed description and its loader."""

from .load import LoadedSystem, load_system
from .schema import FeedSystem

__all__ = ["FeedSystem", "LoadedSystem", "load_system"]
