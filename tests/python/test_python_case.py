"""grainflow.Case: loading, reading and setting keys by their dotted names, validation as on the
command line, and `check()` as a dict."""
import os

import pytest

import grainflow
from conftest import ROOT, gas_case

VIBRATED_BED = os.path.join(ROOT, "cases", "demo", "vibrated_bed.toml")


def test_from_file_reads_keys_with_defaults_and_overrides():
    case = grainflow.Case.from_file(VIBRATED_BED, set={"run.duration": 0.1, "contact.friction": 0.3})
    assert case.engine == "dem" and case.dimension == 3
    assert case["run.duration"] == 0.1
    assert case["contact.friction"] == 0.3
    assert case["species.0.count"] == 239           # from the file (Lan's 239 glass spheres)
    assert case["species.0.diameter"] == pytest.approx(0.003)
    assert case.overrides == ["run.duration=0.1", "contact.friction=0.3"]


def test_setting_a_key_validates_it_and_keeps_the_case_on_error():
    case = grainflow.Case.from_file(VIBRATED_BED)
    case["contact.friction"] = 0.25
    assert case["contact.friction"] == 0.25
    with pytest.raises(grainflow.InputError) as error:
        case["contact.friction"] = -1.0
    assert error.value.key == "contact.friction"
    assert "negative" in error.value.reason
    assert error.value.file.startswith(VIBRATED_BED)
    assert case["contact.friction"] == 0.25          # unchanged by the refused value


def test_unknown_key_raises_input_error_naming_it():
    with pytest.raises(grainflow.InputError) as error:
        grainflow.Case.from_file(VIBRATED_BED, set={"contact.frictoin": 0.3})
    assert error.value.key == "contact.frictoin"
    assert "unknown key" in error.value.reason


def test_combined_checks_run_as_on_the_command_line():
    # A time step longer than the contact allows is a check of keys together (validate_case).
    with pytest.raises(grainflow.InputError) as error:
        grainflow.Case.from_string(gas_case("dem", 3), set={"run.time_step": 0.01})
    assert "time_step" in error.value.key or "time_step" in str(error.value)


def test_syntax_error_names_the_label():
    with pytest.raises(grainflow.InputError) as error:
        grainflow.Case.from_string("[engine\nkind = 1", label="broken.toml")
    assert error.value.file == "broken.toml"


def test_check_reports_the_derived_quantities():
    case = grainflow.Case.from_string(gas_case("dem", 3))
    report = case.check()
    assert report["valid"] is True
    # kn = 1e5 on spheres of mass pi/6: the binary contact lasts pi sqrt(m_eff / kn), m_eff = m / 2.
    import math
    duration = math.pi * math.sqrt(math.pi / 12.0 / 1.0e5)
    assert float(report["contact duration (binary)"].split()[0]) == pytest.approx(duration, rel=1e-5)
    assert report["steps to run"] == "20000"       # duration 2 / time step 1e-4


def test_values_of_every_toml_type_round_trip():
    case = grainflow.Case.from_file(VIBRATED_BED)
    case["gravity.vector"] = [0.0, 0.0, -4.905]
    case["output.snapshot_interval"] = 0
    assert case["gravity.vector"] == [0.0, 0.0, -4.905]
    edmd = grainflow.Case.from_string(gas_case("edmd", 2))
    edmd["collision.restitution"] = 0.9
    assert edmd["collision.restitution"] == 0.9 and edmd.engine == "edmd" and edmd.dimension == 2
