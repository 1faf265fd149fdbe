"""contact_ode from Python: the registries, solve() against the C++ executables and the closed
forms, and the error paths. Run by CTest (tests/CMakeLists.txt) with the module on PYTHONPATH."""
import concurrent.futures
import csv
import json
import math
import multiprocessing
import os
import pathlib
import pickle
import re
import runpy
import signal
import subprocess
import sys
import threading
import time

import numpy as np
import pytest

import contact_ode as co

EXPERIMENTS = pathlib.Path(os.environ.get("CONTACT_ODE_EXPERIMENTS_DIR", "build/experiments"))
EXAMPLES = pathlib.Path(__file__).resolve().parents[2] / "examples"


def test_registries_list_every_entry_with_units():
    methods = {m["name"]: m for m in co.methods()}
    for name in ["penalty", "game-symplectic", "event-exact", "sequential-impulses", "moreau-jean"]:
        assert name in methods
    assert methods["moreau-jean"]["family"] == "time-stepping"
    scenes = {s["name"]: s for s in co.scenes()}
    h0 = next(p for p in scenes["ball-drop"]["parameters"] if p["name"] == "h0")
    assert h0["unit"] == "m" and h0["default"] > 0
    assert {law["name"] for law in co.laws()} >= {"hooke", "kelvin-voigt", "hertz"}
    assert "cvode-bdf" in {i["name"] for i in co.integrators()}
    assert "event-ode" not in co.methods_for("spring-mass")


def test_methods_for_answers_at_the_parameters_solve_is_given():
    """Hunt-Crossley's law is linear only at e = 1, the chain's default, and the linear-only methods
    (xpbd, mujoco-spring, ode-spring) run it only there: methods_for at e = 0.909 leaves out exactly
    the methods solve() refuses with those parameters (it listed them from the defaults)."""
    at_default = co.methods_for("ball-chain", "hunt-crossley-linear")
    given = co.methods_for("ball-chain", "hunt-crossley-linear", e=0.909)
    assert {"xpbd", "mujoco-spring", "ode-spring"} <= set(at_default) - set(given)
    for method in at_default:
        try:
            co.solve("ball-chain", method, "hunt-crossley-linear", e=0.909, t_end=1e-3)
            refused = False
        except ValueError:
            refused = True
        except co.SolverError:  # ran and failed: not refused (ODE's LCP on the touching chain)
            refused = False
        assert refused == (method not in given), method
    with pytest.raises(ValueError, match="^height: not a parameter of scene 'ball-drop'; accepted: m, g, h0"):
        co.methods_for("ball-drop", height=1.0)
    with pytest.raises(ValueError, match="^e: value 'True' has the wrong type"):
        co.methods_for("ball-drop", e=True)
    with pytest.raises(ValueError, match=re.escape("parameter 'e' = 2 is out of range; accepted range [0, 1]")):
        co.methods_for("ball-drop", e=2.0)


def test_a_scene_names_the_law_it_uses_when_none_is_given():
    """Without a law, the ball drop runs its default_law, Hooke's undamped spring: the penalty
    contact gives back the impact speed (restitution 1 to the solver's tolerance, rtol 1e-8) and
    ignores e, which the Kelvin-Voigt law named instead is tuned to (its exit speed the closed
    form's with gravity, to 1e-6: the default rtol's 1e-8 over a contact's hundred steps)."""
    scenes = {s["name"]: s for s in co.scenes()}
    for s in scenes.values():
        assert s["takes_law"] == bool(s["default_law"]), s["name"]
        if s["takes_law"]:
            assert s["default_law"] in {law["name"] for law in co.laws()}
    assert scenes["ball-drop"]["default_law"] == "hooke"
    plain = co.solve("ball-drop", "penalty", t_end=1.0)
    named = co.solve("ball-drop", "penalty", "hooke", t_end=1.0)
    np.testing.assert_array_equal(plain.y, named.y)
    restitution = -plain.contacts["v_out"][0] / plain.contacts["v_in"][0]
    assert restitution == pytest.approx(1.0, abs=1e-6)
    damped = co.solve("ball-drop", "penalty", "kelvin-voigt", e=0.8, t_end=1.0)
    zeta = co.references.damping_ratio_for_restitution(0.8)
    ref = co.references.kelvin_voigt_contact(m=1.0, k=1e5, zeta=zeta, V=math.sqrt(2 * 9.81), g=9.81)
    assert damped.contacts["v_out"][0] == pytest.approx(ref["exit_speed"], rel=1e-6)


@pytest.mark.parametrize("method", ["penalty", "game-symplectic", "event-ode", "moreau-jean"])
def test_ball_drop_reproduces_the_cpp_executable(tmp_path, method):
    """One paradigm each: the module's samples are the ball_drop executable's, to the CSV's
    printed precision (both run the same solve() with the same settings)."""
    out = tmp_path / "bd"
    subprocess.run([str(EXPERIMENTS / "ball_drop"), "--method", method, "--out", str(out)],
                   check=True, capture_output=True)
    with open(out / "samples.csv") as f:
        rows = [r for r in csv.DictReader(f) if r["method"] == method]
    r = co.solve("ball-drop", method, law="kelvin-voigt", t_end=3.0, sample_dt=0.01)
    assert len(rows) == len(r.t)
    expected = np.array([[float(x["t_s"]), float(x["y_m"]), float(x["v_mps"])] for x in rows])
    got = np.column_stack([r.t, r.y[:, 0], r.y[:, 1]])
    np.testing.assert_allclose(got, expected, rtol=1e-12, atol=1e-15)


def test_exact_bounces_give_the_closed_forms():
    """Apex n of a rigid bounce is e^(2n) h0, and the Zeno time t0 (1 + e) / (1 - e)."""
    h0, e = 2.0, 0.8
    r = co.solve("ball-drop", "event-exact", h0=h0, e=e, t_end=3.0)
    apexes = r.apexes["gap"][:3]
    np.testing.assert_allclose(apexes, [e ** (2 * n) * h0 for n in (1, 2, 3)], rtol=1e-12)
    for n in (1, 2, 3):
        assert co.references.rigid_apex_height(h0, 0.0, 9.81, e, n) == pytest.approx(e ** (2 * n) * h0, rel=1e-14)
    t0 = math.sqrt(2 * h0 / 9.81)
    assert co.references.zeno_time(h0, 0.0, 9.81, e) == pytest.approx(t0 * (1 + e) / (1 - e), rel=1e-14)
    # The impact times are a closed form: n = 2^63 was 2^63 terms, a call that never returned.
    assert co.references.rigid_impact_time(h0, 0.0, 9.81, e, 2 ** 63) == co.references.zeno_time(h0, 0.0, 9.81, e)
    # Thrown up, the ball rises to h0 + v0^2 / 2g before its first impact: no apex, so apex n is still
    # element n - 1 (that rise was element 0, the first apex of every method).
    thrown = co.solve("ball-drop", "event-exact", h0=h0, v0=2.0, e=e, t_end=3.0).apexes["gap"][:2]
    np.testing.assert_allclose(thrown, [co.references.rigid_apex_height(h0, 2.0, 9.81, e, n) for n in (1, 2)],
                               rtol=1e-12)


def test_spring_contact_closed_forms():
    """Without gravity a Hooke contact lasts pi sqrt(m/k) and sinks V sqrt(m/k)."""
    m, k, V = 2.0, 1e4, 3.0
    c = co.references.hooke_contact(m, k, V)
    assert c["duration"] == pytest.approx(math.pi * math.sqrt(m / k), rel=1e-14)
    assert c["max_penetration"] == pytest.approx(V * math.sqrt(m / k), rel=1e-14)


def test_advisor_meets_its_budget():
    a = co.advise(m=1.0, v=5.0, e=0.8, max_penetration=1e-3)
    assert a["achieved_penetration"] == pytest.approx(1e-3, rel=1e-3)
    assert a["achieved_restitution"] == pytest.approx(0.8, abs=1e-3)
    # Its arguments refused by their keywords, a value below the smallest normal double too (a
    # 1e-310 kg mass was refused by "power_law_contact", a formula inside).
    with pytest.raises(ValueError, match=re.escape("m: value '1e-310' is below the smallest normal double")):
        co.advise(m=1e-310, v=5.0, e=0.8, max_penetration=1e-3)
    with pytest.raises(ValueError, match=re.escape("max_penetration: value '-1' is out of range")):
        co.advise(m=1.0, v=5.0, e=0.8, max_penetration=-1.0)
    # A budget too small to check by simulation (it once came back "simulated" with an error of 0).
    with pytest.raises(ValueError, match=re.escape("energy_error: value '1e-12' asks for a semi-implicit Euler "
                                                   "step near")):
        co.advise(m=1.0, v=5.0, e=0.8, max_penetration=1e-3, energy_error=1e-12)
    # Gonthier's rule at e = 1e-6 outlasts the check (a RuntimeError naming nothing).
    with pytest.raises(ValueError, match=re.escape("e: value '1e-06' is out of range; accepted range [")):
        co.advise(m=1.0, v=1.0, e=1e-6, law="hunt-crossley-linear", rule="gonthier", max_penetration=1e-3)


def test_advisor_is_the_contact_advisor_program_with_every_option(tmp_path):
    """advise() took a requirement only: its refusal asked for a hertz material (radius, young,
    poisson) it had no keywords for, and it left out the damping rule, the energy error, the engine
    step and g, and the engines' parameters. Every option and every quantity of advice.csv now,
    to the CSV's exact digits."""
    options = dict(m=0.17, v=2.0, e=0.9, law="hertz", rule="gonthier", radius=0.0286, young=2e9,
                   poisson=0.35, energy_error=0.02, engine_step=0.01, g=3.7)
    out = tmp_path / "advice"
    args = [f"--{k.replace('_', '-')}={v}" for k, v in options.items()]
    subprocess.run([str(EXPERIMENTS / "contact_advisor"), *args, "--out", str(out)], check=True,
                   capture_output=True)
    with open(out / "advice.csv") as f:
        rows = {r["quantity"]: r for r in csv.DictReader(f)}
    a = co.advise(**options)
    assert a["law"] == rows.pop("law")["note"]
    assert a["frequency_hz"] == float(rows.pop("frequency")["value"])
    assert set(a) - {"law", "frequency_hz"} == set(rows)
    for quantity, row in rows.items():
        value = float(row["value"])
        if math.isnan(value):
            assert a[quantity] is None, quantity  # a requirement not given
        else:
            assert a[quantity] == value, quantity
    assert a["law"].startswith("hunt-crossley")
    with pytest.raises(ValueError, match=re.escape("rule: value 'x' is not one of: hunt-crossley, "
                                                   "lankarani-nikravesh, flores, gonthier, exact")):
        co.advise(**{**options, "rule": "x"})
    with pytest.raises(ValueError, match=re.escape("radius, young, poisson: give all three")):
        co.advise(m=1.0, v=1.0, e=0.8, law="hertz", radius=0.1)


def test_solve_takes_the_jacobian_and_the_record_limit_as_the_program_does():
    """ball_drop's --jacobian and --max-records had no keywords: an event-ode run could not take
    difference quotients, and a long game run could not keep more than a million records."""
    dq = co.solve("ball-drop", "penalty", "kelvin-voigt", jacobian="dq", t_end=1.0)
    reference = co.solve("ball-drop", "penalty-dq", "kelvin-voigt", t_end=1.0)
    np.testing.assert_array_equal(dq.y, reference.y)  # penalty-dq is penalty with dq, nothing else
    assert dq.stats["rhs_evals"] > co.solve("ball-drop", "penalty", "kelvin-voigt", t_end=1.0).stats["rhs_evals"]
    with pytest.warns(UserWarning, match="jacobian has no effect on method 'penalty-dq'"):
        co.solve("ball-drop", "penalty-dq", jacobian="analytic", t_end=0.1)
    with pytest.raises(ValueError, match=re.escape("jacobian: value 'x' is not one of: analytic, dq")):
        co.solve("ball-drop", "event-ode", jacobian="x")
    # The elastic ball bounces every 0.9 s: two records (a contact, an apex) a bounce.
    with pytest.raises(co.SolverError, match="more than 5 contact records") as info:
        co.solve("ball-drop", "event-exact", e=1.0, t_end=10.0, max_records=5)
    assert info.value.status == co.Status.work_limit
    assert co.solve("ball-drop", "event-exact", e=1.0, t_end=10.0, max_records=30).status == co.Status.success
    for bad in (0, 10**9):
        with pytest.raises(ValueError, match=re.escape(f"max_records: value '{bad}' is out of range; "
                                                       "accepted range [1, 100000000]")):
            co.solve("ball-drop", "event-exact", max_records=bad)


def test_result_has_the_notifications_apex_ledger_and_linear_iterations():
    """The tutorial's batched begin / end notifications, the apexes' contact and ledger and the
    linear iterations were in the C++ result and not in Python's."""
    dt = 1e-3
    r = co.solve("ball-drop", "game-symplectic", "kelvin-voigt", t_end=2.0, dt=dt)
    n = r.notifications
    first = math.ceil(math.sqrt(2 / 9.81) / dt)  # the step in which the ball first reaches the floor
    assert n["begin"].dtype == bool and n["begin"][0] and not n["begin"][1]
    assert n["step"][0] == first
    np.testing.assert_allclose(n["t"], n["step"] * dt, rtol=1e-12)  # delivered at a step's end
    assert int(n["begin"].sum()) == len(r.contacts["t_begin"])
    exact = co.solve("ball-drop", "event-exact", t_end=3.0)
    a = exact.apexes
    assert set(a) == {"contact", "t", "gap", "energy", "dissipated"} and (a["contact"] == 0).all()
    np.testing.assert_allclose(a["energy"] + a["dissipated"], exact.energy0, rtol=1e-12)  # the ledger
    chain = co.solve("ball-chain", "penalty", "hooke", n=20, linear_solver="gmres")
    assert chain.stats["linear_iters"] > 0
    assert co.solve("ball-chain", "penalty", "hooke", n=20, linear_solver="band").stats["linear_iters"] == 0
    # An engine's world, built before its run, is timed apart; the project's methods build none.
    assert co.solve("ball-drop", "mujoco", t_end=0.1).stats["setup_cpu_s"] > 0
    assert chain.stats["setup_cpu_s"] == 0


def test_bad_arguments_raise_value_error_naming_them():
    with pytest.raises(ValueError, match="height: not an option of scene 'ball-drop'"):
        co.solve("ball-drop", "penalty", height=1.0)
    with pytest.raises(ValueError, match="rtol: value '2' is out of range"):
        co.solve("ball-drop", "penalty", rtol=2.0)
    with pytest.raises(ValueError, match="t_end: value '-1' is out of range"):
        co.solve("ball-drop", "penalty", t_end=-1.0)
    with pytest.raises(ValueError, match="method: value 'nope' is not one of"):
        co.solve("ball-drop", "nope")
    # Every function names keywords, every one in its message: methods_for and the closed forms said
    # "--law", the advisor "max_penetration / --duration ... --radius".
    with pytest.raises(ValueError, match="^law: value 'nope' is not one of"):
        co.methods_for("ball-drop", "nope")
    with pytest.raises(ValueError, match="^law: value 'nope' is not one of"):
        co.references.linear_law_first_contact("nope", 1.0, 1e4, 0.8, 1.0)
    with pytest.raises(ValueError, match=re.escape("max_penetration / duration: give exactly one requirement "
                                                   "(or, for hertz, radius, young and poisson)")):
        co.advise(m=1.0, v=1.0, e=0.8)
    # The scene as the caller named it, not the model's internal name ("spring_mass").
    with pytest.raises(ValueError, match="cannot run scene 'spring-mass'"):
        co.solve("spring-mass", "event-ode")
    # Parameters each in range that together are not a double: the refusal names them, where it
    # named a body's inner quantity ("cue inverse inertia") or none (a drop's infinite energy).
    with pytest.raises(ValueError, match=re.escape("scene 'snooker' cannot be made of m '0.17', radius '1e-300'")):
        co.solve("snooker", "penalty", radius=1e-300)
    with pytest.raises(ValueError, match=re.escape("scene 'ball-drop': its initial energy is inf J")):
        co.solve("ball-drop", "penalty", h0=1e308)
    # A run refused for its samples is a SolverError under every method (a fixed-step one raised a
    # RuntimeError).
    with pytest.raises(co.SolverError, match="output samples"):
        co.solve("ball-drop", "game-euler", t_end=1e9, dt=1.0)


def test_scene_parameters_outside_their_range_raise_value_error():
    # Each used to reach the solvers: m = 0 tripped ODE's own mass assertion (a RuntimeError), a
    # NaN or infinite value or a restitution above 1 failed mid-run as a non-finite state.
    for scene, method, given, accepted in [
        ("ball-drop", "ode", {"m": 0.0}, "(0, inf)"),
        ("ball-drop", "penalty", {"e": 1.5}, "[0, 1]"),
        ("ball-drop", "penalty", {"h0": -1.0}, "[0, inf)"),
        ("spring-mass", "penalty", {"v0": math.inf}, "(-inf, inf)"),
        ("cradle", "event-ode", {"k": math.nan}, "(0, inf)"),
        ("wedge", "moreau-jean", {"elasticity": 40.0}, "[0, 1]"),
        ("ball-stack", "penalty", {"g": math.inf}, "[0, inf)"),
    ]:
        (name, value), = given.items()
        with pytest.raises(ValueError, match=f"{scene}: parameter '{name}' = .* accepted range {re.escape(accepted)}"):
            co.solve(scene, method, **given)
    # The value in full: at 6 digits a restitution of 1.0000001 read "'e' = 1 is out of range".
    with pytest.raises(ValueError, match=re.escape("parameter 'e' = 1.0000001 is out of range")):
        co.solve("ball-drop", "penalty", e=1.0000001)
    # Below the smallest normal double, as the command line refuses: each reached the solvers, and
    # a 1e-310 s span under CVODE 'succeeded' with a NaN state.
    tiny = re.escape("is below the smallest normal double (2.22507e-308)")
    for given in [{"m": 1e-310}, {"v0": -5e-324}, {"t_end": 1e-310}, {"dt": 1e-310}, {"atol": 1e-310}]:
        with pytest.raises(ValueError, match=f"{next(iter(given))}.* {tiny}; accepted range"):
            co.solve("ball-drop", "penalty", **given)
    drop = {p["name"]: p for p in next(s for s in co.scenes() if s["name"] == "ball-drop")["parameters"]}
    assert drop["e"]["accepted"] == "[0, 1]" and drop["v0"]["accepted"] == "(-inf, inf)"


def test_solver_failure_raises_with_status_time_and_message():
    with pytest.raises(co.SolverError) as info:
        co.solve("ball-drop", "penalty", max_steps=5, t_end=1.0)
    err = info.value
    assert err.status == co.Status.max_steps
    assert 0 < err.t_reached < 1.0
    assert "CV_TOO_MUCH_WORK" in err.solver_message
    assert err.result.t[-1] <= err.t_reached


def test_a_step_beyond_the_stability_bound_raises_diverged_not_the_exploded_state():
    """The default chain at the default 1 ms step is beyond semi-implicit Euler's bound (omega dt = 6.3
    for its fastest mode): the run returned success at 1e43 m/s; it raises now, at the first sample
    whose energy (with what was booked as lost) passed 1e6 times its initial energy."""
    with pytest.raises(co.SolverError, match=r"energy .* unstable at these settings") as info:
        co.solve("ball-chain", "game-symplectic-spring", "kelvin-voigt")
    err = info.value
    assert err.status == co.Status.diverged
    assert 0 < err.t_reached < 0.05
    gain = err.result.energy[-1] + err.result.dissipated[-1] - err.result.energy0
    assert gain > 1e6 * abs(err.result.energy0)  # the last sample shows why
    stable = co.solve("ball-chain", "game-symplectic-spring", "kelvin-voigt", dt=1e-4)
    assert stable.status == co.Status.success and np.abs(np.asarray(stable.y)).max() < 2


CANNOT_FIT_CHILD = """
import resource
limit = 4 << 30  # before the module reads the limit, at its first use
resource.setrlimit(resource.RLIMIT_AS, (limit, limit))
import contact_ode as co
for n in (5e8, 3e7):
    try:
        co.solve("ball-chain", "penalty", "hooke", n=n, linear_solver="band")
    except Exception as e:
        print(type(e).__name__, e)
"""


def test_a_run_that_cannot_fit_is_refused_before_it_starts():
    """A chain of 5e8 balls (the scene accepts up to 1e9) needs terabytes: refused with what it would
    hold (a ValueError, before the run), where it filled the machine until the kernel killed the
    interpreter. Refused before anything is built: make_scene built the initial state (8 GB) to check
    the balls' gaps, so a process that may hold 4 GB raised MemoryError('std::bad_alloc'), and one
    without a limit wrote 8 GB first. The child runs under that 4 GB address-space limit; a chain
    whose state fits (3e7 balls, 0.48 GB) is refused by solve() for the run's samples and work."""
    child = subprocess.run([sys.executable, "-c", CANNOT_FIT_CHILD], capture_output=True, text=True,
                           env=os.environ, timeout=120)
    assert child.returncode == 0, child.stderr
    lines = child.stdout.splitlines()
    assert len(lines) == 2, child.stdout
    # 2.15 GB: half the 4 GB limit (less on a machine or container with less than 4 GB).
    held = r"a run may hold (2\.15|[01](\.\d+)?) GB \(half the memory this process may use\)"
    assert re.fullmatch(r"ValueError scene 'ball-chain' at n = 5e\+08: its state alone is 1e\+09 values \(8 GB\); "
                        + held + ": fewer bodies", lines[0]), lines[0]
    assert re.fullmatch(r"ValueError penalty on ball-chain needs about \d+\.\d GB \(201 output samples of its "
                        r"6e\+07 state values, .*\); " + held + ": .*a wider sample_dt", lines[1]), lines[1]


def test_the_impact_limit_the_zeno_failure_names_is_a_keyword():
    """ZenoLimit says to raise the impact limit: the keyword max_events does, for the event-driven
    methods (e = 0.8 from 1 m: five bounces to 1.8 s, 20 to 2.4 s; the rest speed ends it near 2.7 s)."""
    with pytest.raises(co.SolverError, match=r"more than 5 impacts before rest .*max_events") as info:
        co.solve("ball-drop", "event-exact", max_events=5)
    assert info.value.status == co.Status.zeno_limit
    assert co.solve("ball-drop", "event-ode", max_events=200).status == co.Status.success
    with pytest.raises(ValueError, match=re.escape("max_events: value '0' is out of range; accepted range [1, inf)")):
        co.solve("ball-drop", "event-ode", max_events=0)
    assert "max_events" in next(m for m in co.methods() if m["name"] == "event-exact")["settings"]


def test_example_reproduces_the_heights_figure(tmp_path):
    out = tmp_path / "heights.png"
    runpy.run_path(str(EXAMPLES / "ball_drop_heights.py"))["main"](str(out))
    assert out.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"


def test_the_readme_session_prints_what_it_shows():
    """The README's Python session, run as a doctest: its outputs are the module's."""
    import doctest
    readme = (EXAMPLES.parent / "README.md").read_text()
    test = doctest.DocTestParser().get_doctest(readme, {}, "README.md", "README.md", 0)
    assert len(test.examples) >= 4
    runner = doctest.DocTestRunner(optionflags=doctest.NORMALIZE_WHITESPACE)
    runner.run(test)
    assert runner.summarize(verbose=False).failed == 0


def test_time_stepping_settings_and_types_are_checked():
    with pytest.raises(ValueError, match="substeps: value '0' is out of range; accepted range \\[1, inf\\)"):
        co.solve("ball-drop", "soft-step", substeps=0)
    with pytest.raises(ValueError, match="theta: value '2' is out of range"):
        co.solve("ball-drop", "moreau-jean", theta=2.0)
    with pytest.raises(ValueError, match="iterations: value 'many' has the wrong type; accepted: a whole number$"):
        co.solve("ball-drop", "sequential-impulses", iterations="many")
    # The refusal names the kind a setting takes (it said "the wrong type" alone); an int too large
    # for the setting's C++ integer is out of range, not of the wrong type.
    for name, value, said in [("max_events", 2.0, "has the wrong type; accepted: a whole number"),
                              ("max_steps", 2**63, "is out of range; accepted: a whole number"),
                              ("linear_solver", 3, "has the wrong type; accepted: a string"),
                              ("k", "stiff", "has the wrong type; accepted: a number"),
                              ("warm_start", 1, "has the wrong type; accepted: True or False"),
                              ("max_records", 0.5, "has the wrong type; accepted: a whole number")]:
        with pytest.raises(ValueError, match=re.escape(f"{name}: value '{value}' {said}") + "$"):
            co.solve("ball-drop", "sequential-impulses", **{name: value})
    # A switch is a bool: any object's truth was taken (None ran without warm starting, NaN with it).
    for value in [None, float("nan"), -1.0, 2, "no"]:
        with pytest.raises(ValueError, match=f"warm_start: value '{value}' has the wrong type"):
            co.solve("ball-drop", "sequential-impulses", warm_start=value)
        with pytest.raises(ValueError, match=f"split_impulse: value '{value}' has the wrong type"):
            co.solve("ball-drop", "sequential-impulses", split_impulse=value)
    for value in [False, True, np.bool_(False)]:
        co.solve("ball-drop", "sequential-impulses", warm_start=value, split_impulse=value, t_end=0.1)
    # ... and a bool is not a number: dt=True ran the game loop at a 1 s step, k=True a 1 N/m spring.
    for name, value in [("dt", True), ("iterations", True), ("k", np.bool_(True)), ("t_end", False)]:
        with pytest.raises(ValueError, match=f"{name}: value '{value}' has the wrong type"):
            co.solve("ball-drop", "sequential-impulses", **{name: value})
    # Accepted before, though the command line refuses it: the exact flight then ran the Zeno
    # cascade into the record limit.
    with pytest.raises(ValueError, match=r"rest_speed: value '0' is out of range; accepted range \(0, inf\)"):
        co.solve("ball-drop", "event-exact", rest_speed=0.0, t_end=5.0)


def test_kelvin_voigt_closed_forms_take_gravity():
    """The Kelvin-Voigt contacts with gravity are the module's runs' first contacts (rtol 1e-10:
    1e-7 relative, as the C++ tests); the clamped law's contact lasts its push and then 2 zeta / w
    of free flight until the overlap closes."""
    m, k, e, h0, g = 4.0, 300.0, 0.9, 0.05, 9.81
    V = math.sqrt(2 * g * h0)
    zeta = co.references.damping_ratio_for_restitution(e)
    for law, closed_form in [("kelvin-voigt", co.references.kelvin_voigt_contact),
                             ("kelvin-voigt-clamped", co.references.clamped_kelvin_voigt_contact)]:
        ref = closed_form(m=m, k=k, zeta=zeta, V=V, g=g)
        r = co.solve("ball-drop", "penalty", law=law, m=m, k=k, e=e, h0=h0, rtol=1e-10, atol=1e-14, t_end=1.0)
        c = r.contacts
        assert c["t_end"][0] - c["t_begin"][0] == pytest.approx(ref["duration"], rel=1e-7)
        assert c["max_penetration"][0] == pytest.approx(ref["max_penetration"], rel=1e-7)
        assert c["v_out"][0] == pytest.approx(ref["exit_speed"], rel=1e-7)
    w, wd = math.sqrt(k / m), math.sqrt(k / m) * math.sqrt(1 - zeta ** 2)
    free = co.references.clamped_kelvin_voigt_contact(m=m, k=k, zeta=zeta, V=V)
    assert free["duration"] == pytest.approx((math.pi - 2 * math.asin(zeta)) / wd + 2 * zeta / w, rel=1e-12)


def test_closed_forms_refuse_arguments_outside_their_domain():
    # Each used to return a number that means nothing: a negative damping ratio, NaN for g = 0.
    with pytest.raises(ValueError, match=r"damping_ratio_for_restitution: e = 1.5 is out of range; accepted range \[0, 1\]"):
        co.references.damping_ratio_for_restitution(1.5)
    with pytest.raises(ValueError, match="rigid bounces: g = 0 is out of range"):
        co.references.zeno_time(h0=1.0, v0=0.0, g=0.0, e=0.5)
    with pytest.raises(ValueError, match="kelvin_voigt_contact: zeta = 1.5"):
        co.references.kelvin_voigt_contact(m=1.0, k=1.0, zeta=1.5, V=1.0)
    # A known law without a closed form there gave three NaNs, silently: now refused, naming those it
    # has (the C++ function keeps NaN, which the programs' tables show as a dash).
    with pytest.raises(ValueError, match="law 'hertz' has no closed form here; accepted: hooke, kelvin-voigt, "
                       "kelvin-voigt-clamped"):
        co.references.linear_law_first_contact("hertz", 1.0, 1e5, 0.8, 1.0)
    # Impacts and apexes are counted from 1, as the closed forms read (apex n follows impact n): n = 0
    # was impact 1 again, so [rigid_impact_time(..., n) for n in range(3)] gave T1 twice.
    for name in ("rigid_impact_time", "rigid_apex_height"):
        with pytest.raises(ValueError, match=r"n \(counted from 1: apex n follows impact n\) = 0 is out of range; "
                           r"accepted range whole numbers in \[1, inf\)"):
            getattr(co.references, name)(1.0, 0.0, 9.81, 0.8, 0)


def test_every_function_says_what_it_computes():
    """help() on the module's functions and closed forms shows more than their signatures: the
    registries, the references (with units and where they hold) and solve() each say what they give."""
    for space in (co, co.references):
        for name in dir(space):
            f = getattr(space, name)
            if name.startswith("_") or isinstance(f, type) or not callable(f):
                continue
            # pybind11 puts the signature first; the description follows it.
            text = "\n".join(f.__doc__.splitlines()[1:]).strip()
            assert len(text.split()) >= 8, f"{space.__name__}.{name} has no description: {f.__doc__!r}"
    assert "counted from 1" in co.references.rigid_apex_height.__doc__
    assert "[m]" in co.references.hooke_contact.__doc__


def test_exact_linear_gives_the_closed_forms_and_refuses_a_nonlinear_law():
    """The exact integrator's first contact is the Kelvin-Voigt closed form with gravity to rounding;
    a Hertz contact, which it cannot solve exactly, raises a solver error saying so."""
    r = co.solve("ball-drop", "penalty", "kelvin-voigt", integrator="exact-linear", atol=1e-14, e=0.8)
    c = r.contacts
    zeta = co.references.damping_ratio_for_restitution(0.8)
    ref = co.references.kelvin_voigt_contact(m=1.0, k=1e5, zeta=zeta, V=-c["v_in"][0], g=9.81)
    assert c["v_out"][0] == pytest.approx(ref["exit_speed"], rel=1e-11)
    assert c["max_penetration"][0] == pytest.approx(ref["max_penetration"], rel=1e-11)
    with pytest.raises(co.SolverError, match="not affine") as info:
        co.solve("ball-drop", "penalty", "hertz", integrator="exact-linear")
    assert info.value.status == co.Status.solver_error
    with pytest.warns(UserWarning, match=r"rtol has no effect on integrator 'exact-linear' \(the exact solution"):
        co.solve("ball-drop", "penalty", "kelvin-voigt", integrator="exact-linear", rtol=1e-3)


def test_dt_is_the_step_of_the_integrator_a_penalty_run_uses():
    """dt set only the game step, which penalty and event-driven runs ignore: a fixed-step
    integrator under them was refused with "value '0'" whatever dt was given."""
    def height_error(dt):  # at t = 0.6 s, after the first contact (switches located: order 4 kept)
        r = co.solve("ball-drop", "penalty", integrator="rk4", dt=dt, t_end=0.6, sample_dt=0.6)
        return r, abs(r.y[-1, 0] - reference.y[-1, 0])
    reference = co.solve("ball-drop", "penalty", rtol=1e-12, atol=1e-14, t_end=0.6, sample_dt=0.6)
    coarse, e_coarse = height_error(1e-4)
    fine, e_fine = height_error(5e-5)
    # Every step is dt, but those cut short at a located switch (one begin, one end by 0.6 s).
    assert fine.stats["steps"] == pytest.approx(0.6 / 5e-5, abs=2)
    assert fine.stats["steps"] == pytest.approx(2 * coarse.stats["steps"], abs=4)
    # RK4: 2^4 per halving, within a factor 2: the steps cut short at the switches move with dt
    # (measured 22 here, 28 one halving coarser).
    assert 16 / 2 < e_coarse / e_fine < 16 * 2
    flight = co.solve("ball-drop", "event-ode", integrator="rk4", dt=1e-3, t_end=1.0)
    assert flight.stats["steps"] >= 1000
    with pytest.raises(ValueError, match="dt: value '0' is out of range: euler is a fixed-step method and needs a step"):
        co.solve("ball-drop", "penalty", integrator="euler")
    with pytest.raises(ValueError, match="dt: cvode-bdf cannot run at a fixed step"):
        co.solve("ball-drop", "penalty", dt=1e-4)  # silently ignored before


def test_a_setting_the_method_ignores_is_a_warning():
    with pytest.warns(UserWarning, match="rtol, iterations have no effect on method 'game-euler'; its settings: dt"):
        co.solve("ball-drop", "game-euler", rtol=1e-8, iterations=3, t_end=0.1)
    with pytest.warns(UserWarning, match="iterations has no effect on method 'penalty'"):
        co.solve("ball-drop", "penalty", iterations=3, t_end=0.1)
    import warnings
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        co.solve("ball-drop", "sequential-impulses", iterations=3, erp=0.1, dt=1e-3, t_end=0.1)
        co.solve("ball-drop", "event-ode", rtol=1e-8, rest_speed=1e-6, t_end=0.1)
        co.solve("ball-drop", "penalty", integrator="rk4", dt=1e-4, t_end=0.1)
    # At a fixed step an explicit integrator has no error control: rtol changes nothing in a penalty
    # or event-driven run under one (the same run, contacts included, with and without it).
    for integrator in ["rk4", "gsl-rk8pd", "gsl-rkf45", "arkode-erk"]:
        with pytest.warns(UserWarning, match=f"rtol has no effect on integrator '{integrator}' at a fixed step"):
            tight = co.solve("ball-drop", "penalty", integrator=integrator, dt=1e-4, rtol=1e-12, t_end=1.5)
        plain = co.solve("ball-drop", "penalty", integrator=integrator, dt=1e-4, t_end=1.5)
        assert len(plain.contacts["t_begin"]) == 2, integrator
        assert np.array_equal(tight.y, plain.y), integrator
    with pytest.warns(UserWarning, match="rtol has no effect on integrator 'velocity-verlet' at a fixed step"):
        co.solve("ball-drop", "event-ode", integrator="velocity-verlet", dt=1e-3, rtol=1e-9, t_end=0.1)
    # atol is read at a fixed step too: an event-driven run's rest height is 100 atol (the warning
    # said atol had no effect, and past the Zeno time a coarse one rests the ball 26 bounces sooner).
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        fine = co.solve("ball-drop", "event-ode", integrator="rk4", dt=1e-4, atol=1e-10, t_end=5.0)
        coarse = co.solve("ball-drop", "event-ode", integrator="rk4", dt=1e-4, atol=1e-5, t_end=5.0)
    assert len(coarse.contacts["t_begin"]) < len(fine.contacts["t_begin"])
    with warnings.catch_warnings():  # adaptive, and implicit at a fixed step (Newton reads them)
        warnings.simplefilter("error")
        co.solve("ball-drop", "penalty", integrator="gsl-rk8pd", rtol=1e-9, t_end=0.1)
        co.solve("ball-drop", "penalty", integrator="arkode-dirk", dt=1e-4, rtol=1e-9, t_end=0.1)
    # Every setting a method lists is a keyword solve() accepts.
    with pytest.raises(ValueError) as info:
        co.solve("ball-drop", "penalty", bogus=1)
    accepted = set(str(info.value).split("accepted: ")[1].split(", "))
    for m in co.methods():
        assert set(m["settings"]) <= accepted, m["name"]


# A solve that takes minutes (a 1000-ball chain for 1 s), interrupted by
# SIGINT once it has begun. The module's result says where the run stopped.
INTERRUPTED_CHILD = """
import signal, sys
import contact_ode as co
if sys.argv[1] == "handler":  # a handler of the caller's own, which does not raise
    signal.signal(signal.SIGINT, lambda *_: print("handler ran", flush=True))
print("solving", flush=True)
try:
    co.solve("ball-chain", "penalty", n=1000, t_end=1.0)
    print("finished")
except KeyboardInterrupt:
    print("KeyboardInterrupt")
except co.SolverError as e:
    print(e.status, e.t_reached < 1.0)
# The interrupt ended that run only: the next one runs to its end.
print(co.solve("ball-drop", "penalty", t_end=1.0).status)
"""


def cpu_seconds(pid):
    """The process's CPU time so far (user and system), from /proc."""
    with open(f"/proc/{pid}/stat") as f:
        fields = f.read().rsplit(")", 1)[1].split()  # after the command's name, which may hold spaces
    return (int(fields[11]) + int(fields[12])) / os.sysconf("SC_CLK_TCK")


@pytest.mark.parametrize("handler,outcome", [("default", ["KeyboardInterrupt"]),
                                             ("handler", ["handler ran", "Status.interrupted True"])])
def test_ctrl_c_ends_a_solve_in_progress(handler, outcome):
    """Python's SIGINT handler only marks the signal for the interpreter, which looked at it when
    solve() returned: a Ctrl-C waited for the whole solve. The run stops within a step now and the
    signal goes to Python's handler, or to the caller's."""
    child = subprocess.Popen([sys.executable, "-c", INTERRUPTED_CHILD, handler], stdout=subprocess.PIPE,
                             text=True, env=os.environ)
    assert child.stdout.readline().strip() == "solving"
    # Into the solve, by the child's CPU time: its set-up takes milliseconds, the solve some 5 s.
    # Half a second of wall time was not always enough on a loaded machine: the signal came before
    # the solve had begun, the caller's handler ran, and the solve went on to its end. The first
    # solve imported NumPy (0.2 s of CPU) before its Ctrl-C window opened; the module imports it.
    start = cpu_seconds(child.pid)
    deadline = time.monotonic() + 60
    while cpu_seconds(child.pid) - start < 0.1 and time.monotonic() < deadline:
        time.sleep(0.01)
    child.send_signal(signal.SIGINT)
    try:
        out, _ = child.communicate(timeout=60)
    except subprocess.TimeoutExpired:
        child.kill()
        child.communicate()
        pytest.fail("the solve went on after SIGINT")
    assert out.splitlines() == outcome + ["Status.success"]
    assert child.returncode == 0


def test_a_long_chain_takes_the_linear_solver_its_refusal_names():
    """A chain whose dense Jacobian would not fit is refused with "use the band, klu or gmres
    linear solver", a setting Python had no keyword for. The direct solvers give the dense run to
    rounding (band bitwise, KLU 1e-14); GMRES's iterations stop at a fraction of the tolerance, so
    its run differs within it (rtol 1e-8 over the pulse's 99 contacts: 4e-7 measured, 1e-6 allowed).
    The default, auto, takes band storage where the Jacobian's band is narrower than the system:
    the long chain runs without asking."""
    with pytest.raises(co.SolverError, match="use the band, klu or gmres linear solver"):
        co.solve("ball-chain", "penalty", n=20000, t_end=1e-3, linear_solver="dense")
    long = co.solve("ball-chain", "penalty", n=20000, t_end=1e-3, linear_solver="band")
    assert long.status == co.Status.success
    by_default = co.solve("ball-chain", "penalty", n=20000, t_end=1e-3)
    np.testing.assert_array_equal(by_default.y[-1], long.y[-1])
    dense = co.solve("ball-chain", "penalty", n=100, t_end=0.05, linear_solver="dense")
    for solver in ["auto", "band", "klu", "gmres"]:
        other = co.solve("ball-chain", "penalty", n=100, t_end=0.05, linear_solver=solver)
        np.testing.assert_allclose(other.y[-1], dense.y[-1], atol=1e-6)
    with pytest.raises(ValueError, match="linear_solver: value 'sparse' is not one of: auto, dense, band, klu, gmres"):
        co.solve("ball-chain", "penalty", linear_solver="sparse")
    assert "linear_solver" in next(m for m in co.methods() if m["name"] == "penalty")["settings"]


def test_other_threads_run_during_a_solve_and_threaded_solves_agree():
    """A solve held the GIL throughout, so a Python thread waited for it (and a sweep over threads
    ran one solve at a time). Now a thread woken as the solve starts finishes its own small task
    early in the solve, not as it returns (within its first half: milliseconds of a second-long
    solve, where the GIL held kept it to the solve's last 0.1 ms), an engine's solve too (the engines
    kept the GIL); and solves run side by side in threads, engines among them, give the serial runs
    bitwise (the library keeps no shared state but the stop request; ODE and Siconos hold one world
    at a time)."""

    def finishes_early(solve):
        started, finished = threading.Event(), []

        def task():
            started.wait()
            total = sum(range(1000))
            finished.append((time.monotonic(), total))

        worker = threading.Thread(target=task)
        worker.start()
        solve_start = time.monotonic()
        started.set()
        solve()
        solve_end = time.monotonic()
        worker.join()
        return finished[0][0] - solve_start < 0.5 * (solve_end - solve_start)

    assert finishes_early(lambda: co.solve("ball-chain", "penalty", n=100, t_end=0.04))  # about a second
    for method in ["siconos", "mujoco"]:
        assert finishes_early(lambda: co.solve("ball-chain", method, n=100, t_end=2.0)), method

    methods = ["penalty", "event-ode", "sequential-impulses", "game-symplectic", "moreau-jean", "bullet", "ode",
               "ode-quick", "mujoco", "siconos"]
    serial = {m: co.solve("ball-drop", m, t_end=1.0).y for m in methods}
    with concurrent.futures.ThreadPoolExecutor(4) as pool:
        runs = list(pool.map(lambda m: (m, co.solve("ball-drop", m, t_end=1.0).y), methods * 3))
    for method, y in runs:
        assert np.array_equal(y, serial[method]), method


def assert_same_result(a, b):
    for name in ["method", "state_labels", "status", "t_reached", "message", "energy0", "stats"]:
        assert getattr(a, name) == getattr(b, name), name
    for name in ["t", "y", "energy", "dissipated"]:
        np.testing.assert_array_equal(getattr(a, name), getattr(b, name))
    for name in ["contacts", "apexes", "notifications"]:
        ours, theirs = getattr(a, name), getattr(b, name)
        assert ours.keys() == theirs.keys()
        for key in ours:
            np.testing.assert_array_equal(ours[key], theirs[key])
            assert ours[key].dtype == theirs[key].dtype


def drop_ball(method):  # a worker process's task (by name: pickle cannot carry co.solve itself)
    return co.solve("ball-drop", method)


def test_a_result_and_a_failure_cross_processes_whole():
    """A Result could not be pickled ("cannot pickle 'contact_ode.Result' object"), so a sweep over
    processes (ProcessPoolExecutor, multiprocessing) could not return one, nor a SolverError (its
    .result). Both travel now and arrive bitwise: every record, the statistics and how the run ended
    (a penalty run's contacts and apexes, a game loop's notifications, an event-driven run's)."""
    runs = [co.solve("ball-drop", method) for method in ["penalty", "game-euler", "event-exact"]]
    assert all(len(r.contacts["t_begin"]) >= 3 and len(r.apexes["t"]) >= 2 for r in runs)
    assert len(runs[1].notifications["t"]) > 0
    for run in runs:
        assert_same_result(pickle.loads(pickle.dumps(run)), run)
    with pytest.raises(co.SolverError) as failed:
        co.solve("ball-drop", "penalty", max_steps=10)
    again = pickle.loads(pickle.dumps(failed.value))
    assert (str(again), again.status, again.t_reached) == (str(failed.value), co.Status.max_steps,
                                                            failed.value.t_reached)
    assert_same_result(again.result, failed.value.result)
    # A state of another layout (its version, first) is refused by name, not read as this one; so
    # is one whose samples are shorter than its state labels (Result.y would read past them).
    state = runs[0].__reduce_ex__(2)[2]
    for tampered, refusal in [((7,) + state[1:], "a pickled contact_ode.Result of another layout"),
                              (state[:2] + (state[2] + ["extra"],) + state[3:], "samples do not match its state labels")]:
        with pytest.raises(ValueError, match=refusal):
            co.Result.__new__(co.Result).__setstate__(tampered)
    context = multiprocessing.get_context("fork")
    with concurrent.futures.ProcessPoolExecutor(2, mp_context=context) as pool:
        in_processes = list(pool.map(drop_ball, ["penalty", "game-euler", "event-exact"]))
    for ours, theirs in zip(in_processes, runs):
        np.testing.assert_array_equal(ours.y, theirs.y)


def test_the_scipy_peer_runs_tuned_and_at_its_defaults():
    """python/scipy_peer.py, the benchmarks' and work_precision's peer: tuned (restarted at each
    switch, analytic Jacobian) and at its defaults (one solve stepping across the switches). Both
    find the drop's five bounces in 3 s; the defaults' apexes stay within a millimetre of the tuned
    ones at rtol 1e-6 (an error-controlled step across a kink is rejected until it meets the
    tolerance: 1.2e-4 m measured for RK45, the loosest). An unknown setup is refused by name."""
    peer = pathlib.Path(__file__).resolve().parents[2] / "python" / "scipy_peer.py"
    args = [sys.executable, str(peer), "--k", "1e5", "--c", "44.8", "--t-end", "3", "--rtols", "1e-6",
            "--atol", "1e-9", "--methods", "LSODA,RK45"]
    out = subprocess.run(args + ["--setups", "tuned,defaults"], capture_output=True, text=True, check=True)
    runs = {(r["setup"], r["method"]): r for r in map(json.loads, out.stdout.splitlines())}
    assert set(runs) == {(s, m) for s in ("tuned", "defaults") for m in ("LSODA", "RK45")}
    for method in ("LSODA", "RK45"):
        tuned, defaults = runs["tuned", method]["apexes"], runs["defaults", method]["apexes"]
        assert len(tuned) == len(defaults) == 5, method
        np.testing.assert_allclose(defaults, tuned, atol=1e-3, err_msg=method)
    refused = subprocess.run(args + ["--setups", "fast"], capture_output=True, text=True)
    assert refused.returncode != 0 and "--setups: value 'fast'" in refused.stderr


def test_the_scipy_peer_solves_the_projects_ball_drop():
    """The peer's pieces are the project's law (the fairness of the benchmarks' ratios rests on it):
    each analytic Jacobian is its right-hand side's derivative (both linear, so a difference
    quotient of step 1 is exact to rounding), and tuned at rtol 1e-9 every method's five apexes are
    the closed form's -- each contact's exit speed from references.kelvin_voigt_contact with gravity,
    each flight's apex v^2 / 2g -- to 1e-6 m (the error the tolerance allows is 1e-9 of the metre)."""
    peer = runpy.run_path(str(pathlib.Path(__file__).resolve().parents[2] / "python" / "scipy_peer.py"))
    m, g, k, e = 1.0, 9.81, 1e5, 0.8
    zeta = co.references.damping_ratio_for_restitution(e)
    c = 2 * zeta * math.sqrt(k * m)
    free, spring, jac_free, jac_spring = peer["smooth_pieces"](m, g, k, c)
    y = np.array([-0.01, -3.0])
    for f, jac in ((free, jac_free), (spring, jac_spring)):
        quotient = np.column_stack([f(0.0, y + step) - f(0.0, y) for step in np.eye(2)])
        np.testing.assert_allclose(jac(0.0, y), quotient, rtol=1e-9, atol=1e-9)
    speed, exact = math.sqrt(2 * g), []
    for _ in range(5):
        speed = co.references.kelvin_voigt_contact(m, k, zeta, speed, g)["exit_speed"]
        exact.append(speed**2 / (2 * g))
    for method in ("BDF", "Radau", "LSODA", "RK45"):
        _, apexes, _, _ = peer["drop"](method, 1e-9, 1e-12, m, g, k, c, 1.0, 0.0, 3.0)
        np.testing.assert_allclose(apexes[:5], exact, rtol=0, atol=1e-6, err_msg=method)


def test_the_engine_settings_reach_their_methods():
    """erp and contact_hertz set what their names say, read off exact consequences (each keyword
    could have set another field unnoticed). Sequential impulses without split impulses push a
    plastic landing's overlap out by Baumgarte's erp / dt alone: each step leaves 1 - erp of it, to
    rounding (a few roundings of overlaps of 1e-4 m, held to 1e-12 of their ratio).
    A ball resting under the soft step settles where a sub-step's soft solve leaves it still:
    -impulse_scale g h = mass_scale bias_rate s, from Box2D's soft constraint at contact_hertz
    (zeta 10, h = dt / 4), to rounding once the settling has converged (1e-12 of it by 2 s)."""
    dt, erp = 1e-3, 0.2
    r = co.solve("ball-drop", "sequential-impulses", erp=erp, split_impulse=False, e=0.0, h0=0.01, dt=dt,
                 t_end=0.1, sample_dt=dt)
    y = np.asarray(r.y)[:, 0]
    landed = int(np.argmax(y < 0))
    np.testing.assert_allclose(y[landed + 1:landed + 5] / y[landed:landed + 4], 1 - erp, rtol=1e-12)

    dt, hertz, g = 1 / 60, 45.0, 9.81
    h, w = dt / 4, 2 * math.pi * hertz
    a1 = 2 * 10 + h * w
    a2 = h * w * a1
    impulse_scale, mass_scale, bias_rate = 1 / (1 + a2), a2 / (1 + a2), w / a1
    r = co.solve("ball-drop", "soft-step", contact_hertz=hertz, h0=0.0, dt=dt, t_end=2.0, sample_dt=dt)
    settled = -impulse_scale * g * h / (mass_scale * bias_rate)
    assert np.asarray(r.y)[-1, 0] == pytest.approx(settled, rel=1e-10)
