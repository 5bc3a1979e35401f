"""The package's exception and warning classes."""


class NotEnoughMemoryError(MemoryError, ValueError):
    """Work refused before it starts because its estimated memory exceeds what the
    machine has available; the message gives the estimate and what would fit. A
    ``MemoryError`` and, as the case-file checks' refusals, a ``ValueError``."""


class ThirdbodyWarning(UserWarning):
    """A result that lies outside the model or the grid's reach (the ``warnings`` of
    a summary: a contact reaching far from the initial contact point, a large
    approach, mu > 1, an energy balance the cells do not resolve)."""
