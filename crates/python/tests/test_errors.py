"""A bad key or value is the command line's error, as a ValueError, and changes nothing."""

import pytest

import dicesim


def cli_message(dicesim_cli, *args):
    """What the command line prints for a refused command, without its `dicesim: `."""
    done = dicesim_cli(*args, check=False)
    assert done.returncode == 2, done
    return done.stderr.strip().removeprefix("dicesim: ")


@pytest.mark.parametrize(
    "key, value, text",
    [
        ("ground.frition", 1, "1"),
        ("ground.friction", 9, "9"),
        ("ground.friction", "abc", "abc"),
        ("initial.velocity.q", 3, "3"),
        ("integrator.dt", -1.0, "-1.0"),
        ("die.extra_corner_mass", [0, 0, 0], "[0, 0, 0]"),
    ],
)
def test_a_bad_change_raises_the_cli_message_and_changes_nothing(dicesim_cli, key, value, text):
    setup = dicesim.Setup()
    before = setup.to_toml()
    with pytest.raises(ValueError) as raised:
        setup[key] = value
    assert str(raised.value) == cli_message(dicesim_cli, "roll", "--set", f"{key}={text}")
    assert key.split(".")[-1] in str(raised.value) or key in str(raised.value)
    assert setup.to_toml() == before and setup.changes == []


def test_an_unknown_key_is_named_when_read():
    with pytest.raises(ValueError, match="`ground.frition`"):
        dicesim.Setup()["ground.frition"]
    with pytest.raises(ValueError, match="`no.such.key`"):
        dicesim.Setup.describe("no.such.key")


def test_values_read_back_in_their_units():
    s = dicesim.Setup(changes={"initial.velocity.y": 25, "ground.friction_law": "whole-die-norm"})
    assert s["initial.velocity"] == [30.0, 25.0, 0.0]
    assert s["initial.velocity.y"] == 25.0
    assert s["ground.friction_law"] == "whole-die-norm"
    assert s["random.random_orientation"] is False
    assert s["random.seed"] == 1
    # The float given is the float held: shortest round-trip text both ways.
    s["ground.damping"] = 0.0001 * 3  # 0.00030000000000000003
    assert s["ground.damping"] == 0.0001 * 3 != 0.0003
    row = dicesim.Setup.describe("ground.friction")
    assert (row["min"], row["max"], row["default"], row["unit"]) == (0.0, 5.0, 1.2, "")
    assert "ground.friction" in dicesim.Setup.keys()


def test_a_run_refuses_a_change_it_would_not_apply(dicesim_cli):
    setup = dicesim.Setup(changes={"initial.height": 10})
    with pytest.raises(ValueError) as raised:
        dicesim.batch(setup, rolls=10)
    assert str(raised.value) == cli_message(dicesim_cli, "batch", "--rolls", "10", "--set", "initial.height=10")
    with pytest.raises(ValueError, match="random.seed"):
        dicesim.batch(dicesim.Setup(changes={"random.seed": 4}), rolls=10, seed=5)
    with pytest.raises(ValueError, match="the map sets it in every cell"):
        dicesim.basin(dicesim.Setup(changes={"ground.friction": 0.5}), x="ground.friction:0.2:1", res=(3, 3))
    with pytest.raises(ValueError, match="--fit sets `ground.friction`"):
        dicesim.compare(dicesim.Setup(changes={"ground.friction": 0.5}), "weldon", throws=5, fit="ground.friction:0.2:1")


def test_bad_run_arguments_name_themselves():
    with pytest.raises(ValueError, match="rolls=0"):
        dicesim.batch(rolls=0)
    with pytest.raises(ValueError, match="engine="):
        dicesim.batch(rolls=5, engine="gpu")
    with pytest.raises(ValueError, match="dataset="):
        dicesim.compare(dataset="galton")
    with pytest.raises(ValueError, match="x and y both vary"):
        dicesim.basin(x="ground.friction:0.2:1", y="ground.friction:0.3:1", res=(3, 3))
    with pytest.raises(ValueError, match="no preset named `nonesuch`"):
        dicesim.Setup("nonesuch")


def test_a_setup_saves_as_a_preset_and_never_over_a_file_unasked(tmp_path):
    s = dicesim.Setup(changes={"ground.friction": 0.35})
    path = tmp_path / "mine.toml"
    s.save(path)
    assert dicesim.Setup(str(path))["ground.friction"] == 0.35
    with pytest.raises(FileExistsError):
        s.save(path)
    # A path refused for what it is, not for being there, is a ValueError, existing or not.
    (tmp_path / "mine.csv").write_text("id\n")
    with pytest.raises(ValueError, match="expected a .toml file"):
        s.save(tmp_path / "mine.csv")
    s["ground.friction"] = 0.4
    s.save(path, force=True)
    assert dicesim.Setup(str(path))["ground.friction"] == 0.4
