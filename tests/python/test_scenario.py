"""Scenarios from Python: the C++ reader's errors as exceptions."""

import pytest

import mrsim
from conftest import source


def test_load_reads_the_case_study():
    s = mrsim.Scenario.load(source("scenarios/case_study.xml"))
    assert s.robots == ["case_study"]
    assert s.module_count("case_study") == 5
    assert s.joint_axes(0) == ["pitch", "yaw", "pitch", "yaw", "pitch"]


def test_bad_field_raises_scenario_error_naming_file_line_and_field(tmp_path):
    text = open(source("scenarios/case_study.xml")).read()
    bad = text.replace("<Kp>", "<Kp>fast", 1)
    path = tmp_path / "bad.xml"
    path.write_text(bad)
    with pytest.raises(mrsim.ScenarioError) as err:
        mrsim.Scenario.load(str(path))
    e = err.value
    assert isinstance(e, ValueError)
    assert e.file == str(path)
    assert e.line == bad[:bad.index("<Kp>fast")].count("\n") + 1
    assert e.path.endswith("joint/Kp")
    assert "fast" in str(e)


def test_missing_file_and_non_xml_raise_not_crash(tmp_path):
    with pytest.raises(mrsim.ScenarioError):
        mrsim.Scenario.load(str(tmp_path / "none.xml"))
    junk = tmp_path / "junk.xml"
    junk.write_bytes(b"\x00\xff<Scenario><robot>")
    with pytest.raises(mrsim.ScenarioError):
        mrsim.Scenario.load(str(junk))


def test_generated_chain_round_trips_through_xml():
    s = mrsim.Scenario.chain(modules=6, pattern="pitch-yaw", sensors="between",
                             force_sensors=True, friction=0.8)
    assert s.joint_axes() == ["pitch", "yaw"] * 3
    again = mrsim.Scenario.from_xml(s.to_xml())
    assert again == s


def test_bad_chain_options_raise_value_error():
    with pytest.raises(ValueError):
        mrsim.Scenario.chain(modules=0)
    with pytest.raises(ValueError):
        mrsim.Scenario.chain(pattern="diagonal")
    with pytest.raises(ValueError):
        mrsim.Scenario.chain(sensors="everywhere")


def test_unknown_robot_raises_key_error():
    s = mrsim.Scenario.chain(modules=3)
    with pytest.raises(KeyError):
        s.module_count("nobody")
    with pytest.raises(IndexError):
        s.module_count(3)


def test_version_command():
    import subprocess
    import sys
    out = subprocess.run([sys.executable, "-m", "mrsim", "--version"],
                         capture_output=True, text=True, check=True).stdout
    assert out.strip() == "mrsim " + mrsim.__version__
