"""mrsim.Optimizer: mrsim-opt's algorithms in ask/tell form for a Python
objective, generation for generation the run mrsim-opt makes."""

import csv
import math
import subprocess
import threading

import numpy as np
import pytest

import mrsim
from conftest import program

# mrsim-opt --genes sine, written as a Python user writes genes.
SINE_GENES = [("A_pitch", 0, 1.5, 0.5), ("A_yaw", 0, 1.5, 0.5),
              ("phi_pitch", -math.pi, math.pi, 1.0),
              ("phi_yaw", -math.pi, math.pi, 1.0), ("T", 1, 6, 3),
              ("offset_pitch", -0.3, 0.3, 0), ("offset_yaw", -0.3, 0.3, 0)]
EPISODE = 0.5


def flat_task_fitness(genome):
    """The objective mrsim-opt --task flat --genes sine scores, computed
    in Python: the genes on the task's gait, one episode of the task."""
    base = mrsim.Gait(mrsim.task_info("flat")["gait"])
    names = mrsim.gait_parameter_names()
    gait = base.with_parameters(**dict(zip(names, map(float, genome))))
    return mrsim.run_task("flat", gait, seconds=EPISODE)["fitness"]


def run_mrsim_opt(out, algorithm, seed, population, generations, islands):
    subprocess.run(
        [program("mrsim-opt"), "--task", "flat", "--genes", "sine",
         "--algorithm", algorithm, "--seed", str(seed), "--population",
         str(population), "--generations", str(generations), "--islands",
         str(islands), "--episode", str(EPISODE), "--workers", "local:1",
         "--out", str(out), "--quiet"],
        check=True, timeout=240)
    with open(out / "evaluations.csv") as f:
        rows = list(csv.DictReader(f))
    with open(out / "generations.csv") as f:
        gens = list(csv.DictReader(f))
    return rows, gens


@pytest.mark.parametrize("algorithm,islands", [
    ("cmaes", 1), ("ga", 1), ("sa", 1), ("pso", 1), ("random", 1),
    ("cmaes", 2)])
def test_ask_tell_reproduces_mrsim_opts_run_for_the_same_seed(
        tmp_path, algorithm, islands):
    seed, population, generations = 7, 4, 3 * islands
    rows, gens = run_mrsim_opt(tmp_path / "opt", algorithm, seed, population,
                               generations, islands)
    names = [g[0] for g in SINE_GENES]
    opt = mrsim.Optimizer(algorithm, genes=SINE_GENES, seed=seed,
                          population=population, islands=islands)
    assert opt.gene_names == names
    for gen in range(generations):
        genomes = opt.ask()
        theirs = [r for r in rows if int(r["generation"]) == gen]
        # mrsim-opt writes the shortest text that reads back as the same
        # double, so float() gives its values bit for bit.
        expected = np.array([[float(r[n]) for n in names] for r in theirs])
        assert genomes.shape == (population, len(names))
        np.testing.assert_array_equal(genomes, expected,
                                      err_msg="generation %d" % gen)
        fitness = [flat_task_fitness(g) for g in genomes]
        assert fitness == [float(r["fitness"]) for r in theirs]
        opt.tell(fitness)
        assert opt.generation == gen + 1
        assert opt.best["fitness"] == float(gens[gen]["best_so_far"])
    best = [r for r in rows if float(r["fitness"]) == opt.best["fitness"]][0]
    np.testing.assert_array_equal(opt.best["genes"],
                                  [float(best[n]) for n in names])
    assert (opt.best["generation"], opt.best["index"]) == (
        int(best["generation"]), int(best["index"]))


def sphere(genomes):
    return [-(g ** 2).sum() for g in genomes]


def test_cmaes_closes_in_on_a_python_objectives_optimum():
    opt = mrsim.Optimizer("cmaes", genes=[("x", -5, 5, 4), ("y", -5, 5, 4)],
                          seed=3, population=8)
    for _ in range(60):
        opt.tell(sphere(opt.ask()))
    assert opt.best["fitness"] > -1e-8
    assert np.abs(opt.best["genes"]).max() < 1e-4


def sequence(seed, **kw):
    opt = mrsim.Optimizer("ga", genes={"x": (-1, 1), "y": (-2, 2, 1)},
                          seed=seed, population=6, **kw)
    out = []
    for _ in range(4):
        g = opt.ask()
        out.append(g)
        opt.tell(sphere(g))
    return np.array(out)


def test_the_same_seed_gives_the_same_generations_and_another_seed_others():
    np.testing.assert_array_equal(sequence(5), sequence(5))
    assert not np.array_equal(sequence(5), sequence(6))


def test_failed_evaluations_score_as_a_failed_mrsim_opt_episode():
    genes = [("x", -1, 1), ("y", -1, 1)]
    failed = mrsim.Optimizer("cmaes", genes=genes, seed=2, population=4)
    scored = mrsim.Optimizer("cmaes", genes=genes, seed=2, population=4)
    g = failed.ask()
    scored.ask()
    failed.tell([None, float("nan"), -0.5, np.inf])
    scored.tell(np.array([-1e6, -1e6, -0.5, -1e6]))
    np.testing.assert_array_equal(failed.ask(), scored.ask())
    assert failed.best["fitness"] == -0.5 and not failed.best["failed"]
    np.testing.assert_array_equal(failed.best["genes"], g[2])

    every = mrsim.Optimizer("random", genes=genes, seed=2, population=3)
    every.ask()
    every.tell([None] * 3)
    assert every.best["failed"] and every.best["fitness"] == -1e6


def test_tell_takes_run_task_results_as_they_are():
    base = mrsim.Gait(mrsim.task_info("flat")["gait"])
    names = mrsim.gait_parameter_names()
    dicts = mrsim.Optimizer("cmaes", genes="sine", seed=3, population=4)
    floats = mrsim.Optimizer("cmaes", genes="sine", seed=3, population=4)
    results = [mrsim.run_task("flat", base.with_parameters(
        **dict(zip(names, map(float, g)))), seconds=0.2)
        for g in dicts.ask()]
    floats.ask()
    dicts.tell(results)
    floats.tell([r["fitness"] for r in results])
    np.testing.assert_array_equal(dicts.ask(), floats.ask())
    assert dicts.best["fitness"] == floats.best["fitness"]

    failed = mrsim.Optimizer("random", genes=[("x", 0, 1)], population=2)
    failed.ask()
    failed.tell([{"fitness": 5.0, "failed": True}, {"fitness": 1.0}])
    assert failed.best["fitness"] == 1.0
    failed.ask()
    with pytest.raises(ValueError, match=r"fitness\[0\].*'fitness'"):
        failed.tell([{"distance": 1.0}, 0.0])


def test_other_threads_run_while_the_algorithm_works():
    # CMA-ES's update of 700 genes takes a fraction of a second in C++. Two
    # threads asking at once overlap only if that work lets go of the GIL;
    # the one that comes second is refused, not raced.
    opt = mrsim.Optimizer("cmaes", genes=[("x%d" % i, -1, 1)
                                          for i in range(700)],
                          seed=1, population=4)
    refused = []

    def ask():
        try:
            opt.ask()
        except RuntimeError as e:
            refused.append(str(e))

    for _ in range(5):  # each a fresh update; one overlap is enough
        g = opt.ask()
        opt.tell(-(g * g).sum(axis=1))
        other = threading.Thread(target=ask)
        other.start()
        while other.is_alive():
            ask()
        other.join()
        if refused:
            break
    assert refused and "another thread" in refused[0]
    np.testing.assert_array_equal(opt.ask(), opt.ask())


def test_gene_forms_give_the_same_genome():
    forms = [
        [("x", -1, 1, 0.5), ("n", 0, 9, 3)],
        {"x": (-1, 1, 0.5), "n": (0, 9, 3)},
        [{"name": "x", "lower": -1, "upper": 1, "start": 0.5},
         {"name": "n", "lower": 0, "upper": 9, "start": 3}],
    ]
    runs = []
    for genes in forms:
        opt = mrsim.Optimizer("ga", genes=genes, seed=4, population=5)
        runs.append(opt.ask())
    np.testing.assert_array_equal(runs[0], runs[1])
    np.testing.assert_array_equal(runs[0], runs[2])
    assert runs[0][0].tolist() == [0.5, 3]  # generation 0 holds the start
    no_start = mrsim.Optimizer("ga", genes=forms[0], seed=4, population=5,
                               include_start=False)
    assert no_start.ask()[0].tolist() != [0.5, 3]


def test_integer_and_disabled_genes_keep_their_kind():
    opt = mrsim.Optimizer(
        "pso", genes={"n": {"lower": 1, "upper": 8, "integer": True},
                      "k": {"lower": 0, "upper": 1, "start": 0.25,
                            "enabled": False},
                      "x": (0, 1)}, seed=1, population=6)
    assert opt.genes[0]["start"] == 4  # the middle, a whole number
    for _ in range(3):
        g = opt.ask()
        assert (g[:, 0] == np.round(g[:, 0])).all()
        assert ((g[:, 0] >= 1) & (g[:, 0] <= 8)).all()
        assert (g[:, 1] == 0.25).all()
        opt.tell(g[:, 2])


def test_built_in_genes_and_algorithm_settings_are_mrsim_opts():
    opt = mrsim.Optimizer("cmaes", genes="sine", seed=1, population=4,
                          cmaes_sigma=0.1)
    assert opt.gene_names == [g[0] for g in SINE_GENES]
    assert "cmaes_sigma=0.1" in opt.settings
    ga = mrsim.Optimizer("ga", genes="sine", selection="truncation",
                         mutation_rate=0.5, elites=2)
    assert "selection=truncation" in ga.settings
    assert "elites=2" in ga.settings


@pytest.mark.parametrize("kwargs,error,words", [
    (dict(genes=[("x", 1, -1)]), mrsim.GenomeError, ["'x'", "lower 1"]),
    (dict(genes=[("x", 0, 1, 2)]), mrsim.GenomeError, ["'x'", "start 2"]),
    (dict(genes={"x": (0,)}), ValueError, ["'x'", "(lower, upper)"]),
    (dict(genes={"x": {"lower": 0, "top": 1}}), ValueError,
     ["'x'", "'top'"]),
    (dict(genes=[("x", "a", 1)]), TypeError, ["'x' lower", "'a'"]),
    (dict(genes=[("x", 0, 1), ("x", 0, 2)]), mrsim.GenomeError,
     ["'x'", "repeated"]),
    (dict(genes=[3]), TypeError, ["genes[0]"]),
    (dict(genes=[]), mrsim.GenomeError, ["no genes"]),
    (dict(genes=[("x", 0, 1)], pso_c1=1.0), TypeError,
     ["pso_c1", "cmaes_sigma"]),
    (dict(genes=[("x", 0, 1)], cmaes_sigma=2.0), ValueError, ["sigma"]),
    (dict(genes=[("x", 0, 1)], population=1), ValueError, ["population"]),
])
def test_bad_input_names_the_gene_field_or_setting(kwargs, error, words):
    with pytest.raises(error) as e:
        mrsim.Optimizer("cmaes", **kwargs)
    for w in words:
        assert w in str(e.value)


def test_unknown_algorithm_names_the_known_ones():
    with pytest.raises(ValueError) as e:
        mrsim.Optimizer("nelder-mead", genes=[("x", 0, 1)])
    assert "cmaes" in str(e.value) and "nelder-mead" in str(e.value)


def test_tell_checks_what_was_asked():
    opt = mrsim.Optimizer("cmaes", genes=[("x", 0, 1)], population=4)
    with pytest.raises(ValueError, match="ask"):
        opt.tell([1, 2, 3, 4])
    first = opt.ask()
    np.testing.assert_array_equal(opt.ask(), first)  # the same generation
    with pytest.raises(ValueError, match="3 fitness values for the 4"):
        opt.tell([1, 2, 3])
    with pytest.raises(TypeError, match=r"fitness\[1\]"):
        opt.tell([1, "x", 3, 4])
    assert opt.generation == 0 and opt.best is None
