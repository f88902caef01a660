"""Key names and what they trigger: demo bindings win, global actions keep a key (no window)."""

from pointmass.app.keymap import KeyAction, KeyMap, key_name


def test_key_names_match_the_demo_spelling():
    assert key_name("_1") == "1"
    assert key_name("NUM_3") == "3"
    assert key_name("RETURN") == "ENTER"
    assert key_name("SPACE") == "SPACE"
    assert key_name("a") == "A"


def test_global_keys():
    keys = KeyMap()
    assert keys.resolve("SPACE") == KeyAction("action", "pause")
    assert keys.resolve("P") == KeyAction("action", "pause")
    assert keys.resolve("RIGHT") == KeyAction("action", "step")
    assert keys.resolve("BACKSPACE") == KeyAction("action", "reset")
    assert keys.resolve("R") == KeyAction("action", "reset")
    assert keys.resolve("MINUS").name == "slower"
    assert keys.resolve("EQUAL").name == "faster"
    assert keys.resolve("V").name == "record"
    assert keys.resolve("TAB").name == "panel"
    assert keys.resolve("C").name == "contacts"
    assert keys.resolve("F1").name == "help"
    assert keys.resolve("H").name == "help"
    assert keys.resolve("Q") == KeyAction("none")


def test_ctrl_p_is_a_screenshot_and_other_ctrl_keys_do_nothing():
    keys = KeyMap({"P": ("Demo P", None)})
    assert keys.resolve("P", ctrl=True) == KeyAction("action", "screenshot")
    assert keys.resolve("SPACE", ctrl=True) == KeyAction("none")


def test_demo_binding_wins_and_p_still_pauses():
    keys = KeyMap({"SPACE": ("Fire", None), "1": ("Pistol", None)})
    assert keys.resolve("SPACE") == KeyAction("demo", "SPACE")
    assert keys.resolve("1") == KeyAction("demo", "1")
    assert keys.resolve("P") == KeyAction("action", "pause")
    assert keys.keys_for("pause") == ["P"]


def test_help_says_which_keys_the_demo_took():
    rows = dict(KeyMap({"SPACE": ("Fire", None)}).help_rows())
    assert rows["P"].startswith("pause / resume")
    assert "Space: the demo's" in rows["P"]
    assert rows["Space"] == "Fire  [demo]"
    assert rows["Ctrl+P"].startswith("screenshot")
