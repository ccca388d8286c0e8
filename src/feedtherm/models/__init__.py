"""Discretisations of a feed system: each returns a Solution."""
