"""What the demos say to a user: whole descriptions (``pointmass list``, the README gallery), a
hint wherever input is wanted, "did you mean" for a mistyped name."""

from __future__ import annotations

import re
from pathlib import Path

import pytest

from pointmass.cli import main
from pointmass.demo import list_demos, load_demo, summary, unknown_demo_message

README = Path(__file__).resolve().parents[2] / "README.md"
DEMOS = list_demos()


@pytest.mark.parametrize("demo", DEMOS, ids=lambda d: d.name)
def test_descriptions_are_whole_sentences_without_markup(demo):
    text = demo.description
    assert text.endswith((".", ")", "!")), f"{demo.name}: cut mid-sentence: {text!r}"
    assert "`" not in text and "\n" not in text and "  " not in text, text


def test_summary_joins_the_first_paragraph_and_drops_literal_marks():
    doc = """A first line that goes on
    onto a second with ``code`` in it.

    The rest."""
    assert summary(doc) == "A first line that goes on onto a second with code in it."


def test_readme_gallery_rows_carry_the_whole_descriptions():
    """scripts/make_gallery.py writes these rows; a cut description would show here."""
    text = README.read_text()
    for demo in DEMOS:
        row = next(line for line in text.splitlines()
                   if line.startswith(f"| **{demo.title}** |"))
        assert f"| {demo.description} |" in row, demo.name


def test_pointmass_list_prints_every_description_whole(capsys):
    assert main(["list"]) == 0
    out = capsys.readouterr().out
    for demo in DEMOS:
        assert demo.description in out


@pytest.mark.parametrize("demo", [d for d in DEMOS if d.keys], ids=lambda d: d.name)
def test_demos_that_take_keys_say_so_on_screen(demo):
    """A demo with keys of its own has a HINT (the window shows it until the first press),
    naming a key it binds; ASCII only (ImGui's default font has no dashes or bullets)."""
    hint = demo.hint
    assert hint, f"{demo.name} binds {sorted(demo.keys)} but shows no hint"
    assert hint.isascii(), hint
    words = set(re.findall(r"[A-Za-z0-9]+", hint.upper()))
    named = {k for k in demo.keys if k in words} | ({"CLICK"} & set(demo.keys)
                                                    if "CLICK" in words else set())
    ranges = re.findall(r"\b(\d)-(\d)\b", hint)
    assert named or ranges, f"{demo.name}: the hint names none of its keys: {hint!r}"


def test_big_ballistic_says_to_click():
    assert "click" in load_demo("big_ballistic").hint.lower()


@pytest.mark.parametrize("typo, meant", [("bal_pit", "ball_pit"), ("boxtower", "box_tower"),
                                         ("ragdol", "ragdoll"), ("Fireworks", "fireworks")])
def test_an_unknown_name_gets_did_you_mean(typo, meant):
    message = unknown_demo_message(typo)
    assert f"did you mean {meant!r}" in message or f"or {meant!r}" in message, message
    with pytest.raises(ValueError, match="did you mean"):
        load_demo(typo)


def test_a_name_like_nothing_gets_the_list_only():
    message = unknown_demo_message("zzzzzz")
    assert "did you mean" not in message and "ball_pit" in message


def test_the_cli_says_did_you_mean(capsys, tmp_path):
    assert main(["render", "bal_pit", "-o", str(tmp_path / "x.png")]) == 2
    err = capsys.readouterr().err
    assert "did you mean 'ball_pit'" in err and err.count("\n") == 1
