"""Errors raised by hydroderiv.

Every error a user can cause derives from :class:`HydroderivError`, so the CLI can print the message
(which names the problem) instead of a traceback.
"""


class HydroderivError(Exception):
    """Base class of the errors a user can cause (bad input, impossible condition, failed run)."""


class GeometryError(HydroderivError):
    """The body geometry is unusable: malformed, open or degenerate surface, or implausible units."""


class ConfigurationError(HydroderivError):
    """An unknown configuration name or an impossible parameter value."""
