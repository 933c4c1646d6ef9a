"""mrsim.optimize runs mrsim-opt with progress; its files read back."""

import os

import pytest

import mrsim
from conftest import BINARY_DIR, source

os.environ.setdefault("MRSIM_BIN_DIR", os.path.join(BINARY_DIR, "bin"))


def test_optimize_reports_every_generation_and_reads_the_results(tmp_path):
    rows = []
    out = str(tmp_path / "opt")
    result = mrsim.optimize(source("scenarios/snake11.xml"),
                            source("scenarios/forward_gait.genome.xml"), out,
                            algorithm="random", generations=2, population=3,
                            seed=1, episode=0.5, workers=1,
                            progress=rows.append)
    assert [int(r["generation"]) for r in rows] == [0, 1]
    g = result["generations"]
    assert len(g["best_so_far"]) == 2
    assert g["best_so_far"][1] >= g["best_so_far"][0]
    assert isinstance(result["best_gait"], mrsim.Gait)
    assert mrsim.read_generations(out)["generations"]["best"][0] == rows[0]["best"]


def test_optimize_with_a_bad_genome_raises(tmp_path):
    bad = tmp_path / "bad.genome.xml"
    bad.write_text("<genome><gene name='A_pitch' lower='2' upper='1'/></genome>")
    with pytest.raises(RuntimeError) as e:
        mrsim.optimize(source("scenarios/case_study.xml"), str(bad),
                       str(tmp_path / "opt"), generations=1)
    assert "bad.genome.xml" in str(e.value)


def test_optimize_takes_a_task_and_built_in_genes(tmp_path):
    out = str(tmp_path / "pole")
    result = mrsim.optimize(task="pole", genes="sine", out_dir=out,
                            algorithm="random", generations=1, population=2,
                            seed=1, episode=0.5, workers=1)
    assert len(result["generations"]["best"]) == 1
    # The task's own gait is the base the genes modify.
    assert result["best_gait"].kind == "roll"


def test_optimize_names_the_known_tasks_for_an_unknown_one(tmp_path):
    with pytest.raises(ValueError) as e:
        mrsim.optimize(task="moon", genes="sine", out_dir=str(tmp_path / "o"))
    assert "pole" in str(e.value) and "moon" in str(e.value)
    with pytest.raises(TypeError):
        mrsim.optimize(source("scenarios/snake11.xml"), task="flat",
                       genes="sine", out_dir=str(tmp_path / "o"))


def test_run_task_scores_an_episode_like_mrsim_tasks():
    own = mrsim.run_task("pole", seconds=1.0)
    assert not own["failed"]
    same = mrsim.run_task("pole", mrsim.Gait("helical-pole"), seconds=1.0)
    assert own["fitness"] != same["fitness"]  # not the wrapped gait
    assert mrsim.run_task("flat", seconds=1.0) == mrsim.run_task(
        "flat", seconds=1.0)  # deterministic
    with pytest.raises(ValueError):
        mrsim.run_task("moon")


def test_optimize_tunes_a_lua_controllers_declared_params(tmp_path):
    out = str(tmp_path / "lua")
    script = source("examples/optimise/serpenoid_params.lua")
    result = mrsim.optimize(task="flat", controller="lua:" + script,
                            out_dir=out, algorithm="random", generations=1,
                            population=2, seed=1, episode=0.5, workers=1)
    g = result["generations"]
    assert len(g["best"]) == 1
    # The script's declared params are the genes, with their names.
    assert "amplitude" in g and "phase_lag" in g
    best = open(os.path.join(out, "best_controller.lua")).read()
    assert "function step" in best


def test_optimize_refuses_gait_genes_for_a_controller_with_its_own(tmp_path):
    with pytest.raises(TypeError) as e:
        mrsim.optimize(task="flat", genes="sine",
                       controller="lua:" + source(
                           "examples/optimise/serpenoid_params.lua"),
                       out_dir=str(tmp_path / "o"))
    assert "its own genes" in str(e.value)


def test_optimize_uses_the_setup_saved_in_the_scenario_file(tmp_path):
    # scenarios/optimise_snake.xml: CMA-ES, 4 generations of 4, the sine
    # genes, seed 3, 2 s episodes; generations given here override it.
    out = str(tmp_path / "file")
    result = mrsim.optimize(source("scenarios/optimise_snake.xml"),
                            out_dir=out, generations=1, episode=0.5,
                            workers=1)
    assert len(result["generations"]["best"]) == 1
    assert "A_yaw" in result["generations"]  # the sine genes, from the file
    flags = str(tmp_path / "flags")
    same = mrsim.optimize(source("scenarios/snake11.xml"), genes="sine",
                          out_dir=flags, algorithm="cmaes", generations=1,
                          population=4, seed=3, episode=0.5, workers=1,
                          extra_args=("--w-energy", "0.01"))
    assert (result["generations"]["best"][0] ==
            same["generations"]["best"][0])
