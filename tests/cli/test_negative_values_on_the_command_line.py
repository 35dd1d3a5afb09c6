"""A negative number after ``shift --to KEY`` is the value, not an option: it reaches the
parameter's own check, refused in one line naming ``--to``, the key and the allowed range."""
import pytest

from hubvib.cli import main


@pytest.mark.parametrize("key, text, allowed", [
    ("c_ru", "-1e5", "c_ru = -100000.0, but it must be >= 0.0"),
    ("c_ru", "-1.5E+3", "c_ru = -1500.0, but it must be >= 0.0"),
    ("m_p", "-.5", "m_p = -0.5, but it must be > 0.0"),
    ("alpha_s", "-2", "alpha_s = -2.0, but it must be > 0.0"),
    ("c_ru", "-inf", "c_ru = -inf, but it must be finite"),
])
def test_negative_value_is_refused_by_name_with_its_range(key, text, allowed, capsys):
    assert main(["shift", "--to", key, text]) == 2
    err = capsys.readouterr().err
    assert err == f"hubvib: error: --to {key} {text}: {allowed}\n", err


def test_a_word_after_the_key_is_still_a_usage_error(capsys):
    with pytest.raises(SystemExit) as exit_:
        main(["shift", "--to", "c_ru", "-x"])
    assert exit_.value.code == 2
    assert "argument --to: expected 2 arguments" in capsys.readouterr().err


def test_positive_value_still_shifts(capsys):
    assert main(["shift", "--to", "c_ru", "1e5", "--json"]) == 0
    assert '"modified": 100000.0' in capsys.readouterr().out
