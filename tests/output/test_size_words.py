"""The words of ``pumplink size`` where no design meets the limits (pumplink.output.size)."""

from pumplink.output.size import beyond_limit


def test_a_value_just_beyond_its_limit_is_shown_with_the_digits_that_tell_them_apart():
    """A grip stroke of 1.0028 m against the 1 m limit reads "1.003 m > 1 m" (to three significant
    digits both would read "1 m"); a value three digits tell apart keeps three."""
    assert beyond_limit(1.0028, 1.0, "m", ">") == "1.003 m > 1 m"
    assert beyond_limit(3.3650, 3.3, "m/s", ">") == "3.37 m/s > 3.3 m/s"
    assert beyond_limit(29.96, 30.0, "/min", "<") == "29.96 /min < 30 /min"
