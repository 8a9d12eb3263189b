"""How the report writes a number, shared by its sections."""


def ms(v):
    """Milliseconds (or any time) to 3 significant digits, whole above 100."""
    return f"{v:.3g}" if v < 100 else f"{v:.0f}"


def ratio_text(r):
    return f"{r:.3g}"


def opt(value, spec):
    """A number as `spec`, or "-" for none."""
    return "-" if value is None else format(value, spec)
