"""The self-affine track generator against SurfaceTopography, the field's reference implementation: a line's
spectrum must fall as q^-(1+2H), the 1D exponent (the 2D exponent -2(1+H) would make an H = 0.8 track read q^-3.6)."""
import numpy as np
import pytest

from engine_sim.substrate import self_affine_kernel

ST = pytest.importorskip("SurfaceTopography", reason="SurfaceTopography is not installed (pip install "
                         "'frictionnoise[test]'): the generator is not checked against the reference")


def _exponent(q, C, lo, hi):
    C = np.ma.masked_invalid(C)
    m = (q > lo) & (q < hi) & ~np.ma.getmaskarray(C)
    return -np.polyfit(np.log(q[m]), np.log(np.asarray(C[m])), 1)[0]


@pytest.mark.parametrize("hurst", [0.8, 0.3])
def test_self_affine_line_psd_exponent_and_rms_slope(hurst):
    from SurfaceTopography import UniformLineScan
    from SurfaceTopography.Generation import fourier_synthesis

    lr, ls, rms = 2.0, 0.1, 0.1  # mm: pads_rough_profile's roll-off and cut-off
    dx = ls / 4  # the track's grid
    k = self_affine_kernel(hurst, lr, ls, dx, rms)
    rng = np.random.default_rng(1)
    n = 2**15  # 820 mm, 400 roll-off wavelengths per profile
    Cs, slopes = [], []
    for _ in range(8):
        h = np.convolve(rng.standard_normal(n + len(k) - 1), k, mode="valid")  # as SelfAffineTrack streams it
        line = UniformLineScan(h, n * dx, periodic=False)
        q, C = line.power_spectrum_from_profile()
        Cs.append(np.ma.masked_invalid(C))
        slopes.append(line.rms_slope_from_profile())
    q = np.asarray(q)
    lo, hi = 2 * (2 * np.pi / lr), 0.5 * (2 * np.pi / ls)  # clear of the roll-off and the cut-off
    gamma = _exponent(q, np.ma.mean(np.ma.array(Cs), axis=0), lo, hi)
    # measured 2.58 (H 0.8) and 1.58 (H 0.3); one profile scatters by 0.044, so the 8-profile ensemble by 0.016,
    # plus a bias of ~0.02 from the Hann window and the FIR truncation: 0.1 is 5 sigma beyond it, while a
    # kernel with the 2D exponent reads 1 + 2H + 1, ten times the tolerance away
    assert abs(gamma - (1 + 2 * hurst)) < 0.1, gamma
    # SurfaceTopography's own generator, same cut-offs and band: it reads 0.07 steeper than ours (its roll-off
    # differs; 4 profiles scatter by 0.02), so the two agree within 0.15
    ref = []
    for seed in range(4):
        st = fourier_synthesis((n,), (n * dx,), hurst, rms_slope=rms, long_cutoff=lr, short_cutoff=ls,
                               rng=np.random.default_rng(seed))
        q2, C2 = st.power_spectrum_from_profile()
        ref.append(_exponent(np.asarray(q2), C2, lo, hi))
    assert abs(gamma - np.mean(ref)) < 0.15, (gamma, ref)
    # rms slope: normalised exactly in expectation (sum of the kernel's squared differences); the ensemble
    # mean scatters by 0.3 % (measured 0.0997), so 3 % is a clear margin
    assert np.mean(slopes) == pytest.approx(rms, rel=0.03)
