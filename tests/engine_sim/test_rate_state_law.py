"""The scene's rate-and-state friction law (engine_sim/laws/rate_state.py): its per-step kernel against the exact
solutions of the state laws and of the implicit friction update, its loader checks, and the one-pad spring-slider
scene's onset of stick-slip at k_c = N_pad (B - A) / D_c."""
import math
import pickle
from dataclasses import replace

import numpy as np
import pytest

from compare.cli import main
from engine_sim import ScenarioError, load_scenario, scenario_from_dict
from engine_sim import units as U
from engine_sim.laws.rate_state import rs_step, steady_mu
from engine_sim.scene import Scene, describe

DT = 1e-4  # s (scene units: ms, so the kernel's dt is 0.1)


def _prm(law, A=0.01, B=0.02, Dc=1e-5, V0=1e-4, mu_ref=0.6):
    return np.array([A, B, Dc, V0 * U.VELOCITY, mu_ref, DT, float(law), 1.0 / U.VELOCITY])


@pytest.mark.parametrize("law", [0, 1])
def test_state_update_is_exact_at_constant_speed(law):
    # the body's speed held at V (vp fixed); NA tiny so the friction hardly moves vel. The ageing law's exact
    # solution theta = D_c/V + (theta0 - D_c/V) e^(-V t/D_c); the slip law's ln(V theta/D_c) decays as e^(-V t/D_c).
    # Both updates are the exact solutions stepped, so agreement is to rounding (1e-12 relative over 3000 steps).
    V, Dc, th0 = 1e-4, 1e-5, 0.3
    th = np.array([th0])
    for _ in range(3000):
        vel, vp = np.array([V * U.VELOCITY, 0.0]), np.array([V * U.VELOCITY])
        rs_step(vel, np.array([1e-30]), np.array([1.0]), th, vp, _prm(law), DT * U.TIME, np.zeros(1))
    t = 3000 * DT
    if law == 0:
        exact = Dc / V + (th0 - Dc / V) * math.exp(-V * t / Dc)
    else:
        exact = Dc / V * math.exp(math.log(V * th0 / Dc) * math.exp(-V * t / Dc))
    assert th[0] == pytest.approx(exact, rel=1e-12)


def test_ageing_state_grows_as_time_at_rest():
    th = np.array([0.1])
    for _ in range(1000):
        rs_step(np.zeros(2), np.array([1e-3]), np.array([1.0]), th, np.zeros(1), _prm(0), DT * U.TIME, np.zeros(1))
    assert th[0] == pytest.approx(0.1 + 1000 * DT, rel=1e-12)  # d theta/dt = 1 at V = 0, exact


def test_friction_update_is_backward_euler_and_stable_at_any_slope():
    # one body, no other force: u is the root of h(u) = m (u - v) + dt N A asinh(u e^(psi/A) / (2 V0)) to the
    # solver's absolute 1e-13 v (h changes sign across u +- 1e-12 v); at steady state e^(psi/A) = e^60 the slope
    # dt N A e^60 / (2 V0 m) is ~1e24 times the explicit limit, yet the speed decays monotonically toward rest and
    # never changes sign (an explicit force would flip it every step)
    A, B, Dc, V0, mu_ref = 0.01, 0.02, 1e-5, 1e-4, 0.6
    NA, m, dt = 0.01 * U.FORCE, 1e-3 * U.MASS, DT * U.TIME
    v = 1e-3 * U.VELOCITY
    v_first = v
    th, vp = np.array([0.1]), np.array([v])
    speeds = []

    def h(u, v, ln_s):
        g = math.log(2 * u) + ln_s if ln_s + math.log(u) > 20 else math.asinh(u * math.exp(ln_s))
        return m * (u - v) + dt * NA * g

    for _ in range(20):
        if v == 0.0:  # at rest: the kernel leaves it there
            break
        vel = np.array([v, 0.0])
        rs_step(vel, np.array([NA]), np.array([m]), th, vp, _prm(0, A, B, Dc, V0, mu_ref), dt, np.zeros(1))
        u = vel[0]
        ln_s = (mu_ref + B * math.log(V0 * th[0] / Dc)) / A - math.log(2 * V0 * U.VELOCITY)
        d = 1e-12 * v
        assert h(u + d, v, ln_s) > 0 and (u - d <= 0 or h(u - d, v, ln_s) < 0)
        speeds.append(u)
        v = u
    speeds = np.array(speeds)
    assert np.all(speeds >= 0) and np.all(np.diff(speeds) <= 0) and speeds[-1] < 1e-100 * v_first


def test_regularised_law_matches_the_log_form_and_is_finite_at_rest():
    A, B, V0, mu_ref = 0.12, 0.04, 1e-4, 0.3
    for v in (1e-3, 5e-3, 2e-2):  # asinh(X) = ln(2X) + 1/(4 X^2) + ...: X >= 40 here, so 2e-4 relative
        log_form = mu_ref + (A - B) * math.log(v / V0)
        assert steady_mu(v, A, B, V0, mu_ref) == pytest.approx(log_form, rel=2e-4)
    assert steady_mu(0.0, A, B, V0, mu_ref) == 0.0


def test_slope_is_the_derivative_of_the_steady_force_and_describe_names_the_law():
    sc = load_scenario("pads_rate_state")
    law, load, v = sc.law_part, sc.normal_load_per_pad, sc.steady_velocity
    h = 1e-6 * v
    num = (law.force(v + h, load, 0.0) - law.force(v - h, load, 0.0)) / (2 * h)
    assert law.slope(v, load, 0.0) == pytest.approx(num, rel=1e-6)  # central difference, error O(h^2)
    d = describe(sc)["friction_law"]
    assert d["law"] == "rate_state" and d["b"] == pytest.approx(sc.friction.A - sc.friction.B)
    from compare.analysis.extract import friction_slope
    # the steady slope (A - B) N_pad / v in the log regime: compare's extraction reads it from b and v_c
    assert friction_slope(d, v) == pytest.approx(law.slope(v, load, 0.0), rel=2e-3)
    assert sc.law_part.reduced_model == "model_ageing"


@pytest.mark.parametrize("field,value,match", [
    ("A", 0.0, "friction.A must be > 0"), ("D_c", -1e-5, "friction.D_c must be > 0"),
    ("V0", 0.0, "friction.V0 must be > 0"), ("theta0", 0.0, "friction.theta0 must be > 0"),
    ("D_c", 1e-9, "friction.D_c = 1e-09 m is not resolved by run.dt"),
    ("state_law", "dieterich", "friction.state_law = 'dieterich' is not one of"),
])
def test_out_of_domain_parameters_name_the_field(tmp_path, capsys, field, value, match):
    base = {"friction": {"law": "rate_state", field: value}, "drive": {"kind": "velocity", "v": 5e-3}}
    with pytest.raises(ScenarioError, match=match):
        scenario_from_dict(base)
    path = tmp_path / "bad.toml"
    val = f'"{value}"' if isinstance(value, str) else repr(value)
    path.write_text(f'[friction]\nlaw = "rate_state"\n{field} = {val}\n[drive]\nkind = "velocity"\nv = 5e-3\n')
    assert main(["run", str(path), "--duration", "0.01"]) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and field in err[0]


def _set_stiffness(scene, k):
    """The spring-slider's stiffness k (N/m; the drive spring in series with the pad spring k0), the anchor moved
    so the spring's force is unchanged."""
    sp, k0 = scene.drive.spring, scene.sc.pads.k0
    kd = k * k0 / (k0 - k) * U.STIFFNESS
    F = sp.stiffness * (sp.b.position.x - scene.block.position.x - sp.rest_length)
    sp.stiffness = kd
    sp.b.position = (scene.block.position.x + sp.rest_length + F / kd, sp.b.position.y)


def _amplitudes(scene, T, parts=3):
    n = int(round(T / scene.sc.run.dt_out))
    v = np.empty(n)
    for k in range(n):
        if k % 64 == 0:
            scene.maintain()
        scene.advance(scene.n_sub)
        v[k] = scene.block.velocity.x / U.VELOCITY
    return [np.ptp(seg) / 2 for seg in np.array_split(v, parts)]


@pytest.mark.parametrize("state_law", ["ageing", "slip"])
def test_spring_slider_turns_to_stick_slip_at_k_c(state_law):
    # k_c = N_pad (B - A) / D_c = 991 N/m; the block's inertia raises it by M V^2 / (N_pad A D_c) = 1 % (Rice &
    # Ruina 1983), inside the bracket. Steady sliding is reached at 3 k_c (4 s), the state perturbed by 10 %, then
    # 6 s at 1.1 k_c and at 0.9 k_c from that same state. Linear theory: a growth rate of about -/+(V / 2 D_c)
    # ((B - A)/A)(1 - k/k_c) ~ -/+0.5 1/s, a factor e^(+-2) between the first and last 2 s; the test asks for a
    # factor 3 each way (decay at 1.1 k_c, growth into stick-slip at 0.9 k_c, where the speed reaches 0). Both state
    # laws share k_c and the linear growth rate (measured: 0.163 -> 0.037 V and 0.46 -> 19 V for the ageing law,
    # 0.168 -> 0.038 V and 0.54 -> 12 V for the slip law).
    sc = load_scenario("spring_slider_rate_state")
    sc = replace(sc, friction=replace(sc.friction, state_law=state_law))
    fr = sc.friction
    kc = sc.normal_load_per_pad * (fr.B - fr.A) / fr.D_c
    scene = Scene(sc)
    _set_stiffness(scene, 3 * kc)
    _amplitudes(scene, 4.0)
    assert scene.law.states(scene)[0] == pytest.approx(fr.D_c / sc.drive.v, rel=1e-3)  # steady: theta = D_c / V
    scene.law.theta *= 1.1
    saved = pickle.dumps(scene)
    out = {}
    for f in (1.1, 0.9):
        s = pickle.loads(saved)
        _set_stiffness(s, f * kc)
        out[f] = _amplitudes(s, 6.0)
    assert out[1.1][-1] < out[1.1][0] / 3
    assert out[0.9][-1] > 3 * out[0.9][0] and out[0.9][-1] > 0.9 * sc.drive.v


def test_checkpoint_keeps_the_states():
    sc = load_scenario("pads_rate_state")
    sc = replace(sc, pads=replace(sc.pads, N=3))
    s = Scene(sc)
    s.advance(50)
    th = s.law.states(s).copy()
    s2 = pickle.loads(pickle.dumps(s))
    assert np.array_equal(s2.law.states(s2), th)
    s.advance(20)
    s2.advance(20)
    assert np.array_equal(s2.law.states(s2), s.law.states(s))
