"""trispline kernels: Lattice, ffd_evaluate (cpu_fast against cpu_ref), FfdEvaluator, certify, silhouettes."""
import numpy as np
import pytest
import trispline

LO, HI = np.array([-1.0, 0.0, 2.0]), np.array([1.0, 3.0, 2.5])


def cloud(n=5000, seed=0):
    return LO + np.random.default_rng(seed).random((n, 3)) * (HI - LO)


def bent(L, seed=1):
    cp = L.control_points
    cp += np.random.default_rng(seed).uniform(-0.05, 0.05, cp.shape) * (HI - LO)
    return L.with_control_points(cp)


def test_identity_maps_points_to_themselves():
    L = trispline.Lattice.identity(bounds=(LO, HI), controls=(5, 4, 6), orders=(4, 3, 2))
    assert L.orders == (4, 3, 2) and L.control_points.shape == (5, 4, 6, 3)
    pts = cloud()
    P, N = trispline.ffd_evaluate(L, pts, backend="cpu_ref")
    assert N is None and np.abs(P - pts).max() < 1e-12
    P, _ = trispline.ffd_evaluate(L, pts)  # cpu_fast: float, within 1e-5 of the diagonal
    assert np.abs(P - pts).max() < 1e-5 * np.linalg.norm(HI - LO)


def test_a_moved_control_point_moves_points_near_it():
    L = trispline.Lattice.identity(bounds=(LO, HI), controls=(4, 4, 4), orders=(4, 4, 4))
    cp = L.control_points
    cp[3, 3, 3] += (0.0, 0.5, 0.0)
    moved = L.with_control_points(cp)
    corner, far = np.array([HI]), np.array([LO])
    assert trispline.ffd_evaluate(moved, corner, backend="cpu_ref")[0][0, 1] == pytest.approx(HI[1] + 0.5)
    assert np.allclose(trispline.ffd_evaluate(moved, far, backend="cpu_ref")[0], far, atol=1e-12)


def test_cpu_fast_agrees_with_cpu_ref():
    L = bent(trispline.Lattice.identity(bounds=(LO, HI), controls=(6, 6, 6), orders=(4, 4, 4)))
    pts = cloud(20000)
    normals = np.random.default_rng(2).normal(size=pts.shape)
    normals /= np.linalg.norm(normals, axis=1, keepdims=True)
    Pf, Nf = trispline.ffd_evaluate(L, pts, normals=normals)
    Pr, Nr = trispline.ffd_evaluate(L, pts, backend="cpu_ref", normals=normals)
    diag = np.linalg.norm(np.ptp(L.control_points.reshape(-1, 3), axis=0))
    assert np.abs(Pf - Pr).max() < 1e-5 * diag
    assert np.allclose(np.linalg.norm(Nf, axis=1), 1.0, atol=1e-5)
    angle = np.arctan2(np.linalg.norm(np.cross(Nf, Nr), axis=1), (Nf * Nr).sum(axis=1))
    assert angle.max() < 1e-4  # the accuracy contract of core/ffd/ffd_evaluator.h


def test_normals_follow_the_cofactor_transform():
    # A stretch by 2 along x: positions scale, unit normals n ∝ cof(J)·n = (n_x/2, n_y, n_z) normalised.
    L = trispline.Lattice.identity(bounds=(LO, HI), controls=(2, 2, 2), orders=(2, 2, 2))
    cp = L.control_points
    cp[..., 0] = 2 * cp[..., 0]
    stretched = L.with_control_points(cp)
    pts = cloud(100)
    n = np.tile([[1.0, 1.0, 0.0]], (100, 1)) / np.sqrt(2)
    for backend in ("cpu_ref", "cpu_fast"):
        P, N = trispline.ffd_evaluate(stretched, pts, backend=backend, normals=n)
        assert np.allclose(P[:, 0], 2 * pts[:, 0], atol=1e-5)
        expected = np.array([0.5, 1.0, 0.0]) / np.linalg.norm([0.5, 1.0, 0.0])
        assert np.allclose(N, expected, atol=1e-5)


def test_evaluator_binds_once_and_follows_the_lattice():
    L = trispline.Lattice.identity(bounds=(LO, HI), controls=(4, 4, 4), orders=(3, 3, 3))
    pts = cloud(1000)
    ev = trispline.FfdEvaluator(L, pts)
    assert ev.vertex_count == 1000 and ev.backend == "cpu_fast"
    P0, _ = ev.evaluate()
    moved = bent(L)
    ev.set_lattice(moved)
    P1, _ = ev.evaluate()
    assert np.abs(P1 - trispline.ffd_evaluate(moved, pts)[0]).max() < 1e-12
    assert not np.shares_memory(P0, P1) and np.abs(P1 - P0).max() > 1e-3


def test_evaluator_writes_into_out_arrays():
    L = trispline.Lattice.identity(bounds=(LO, HI), controls=(4, 4, 4), orders=(3, 3, 3))
    pts = cloud(500)
    normals = np.tile([[0.0, 1.0, 0.0]], (500, 1))
    for backend in ("cpu_fast", "cpu_ref"):
        ev = trispline.FfdEvaluator(bent(L), pts, backend=backend, normals=normals)
        fresh_p, fresh_n = ev.evaluate()
        P, N = np.full((500, 3), np.nan), np.full((500, 3), np.nan)
        rp, rn = ev.evaluate(out=(P, N))
        assert rp is P and rn is N
        assert np.array_equal(P, fresh_p) and np.array_equal(N, fresh_n)
        with pytest.raises(ValueError, match="shape"):
            ev.evaluate(out=(np.zeros((499, 3)), N))
        with pytest.raises(ValueError, match="float64"):
            ev.evaluate(out=(np.zeros((500, 3), dtype=np.float32), N))
        with pytest.raises(ValueError, match="C-contiguous"):
            ev.evaluate(out=(np.zeros((3, 500)).T, N))


def test_lattice_from_parameters_and_knots():
    cp = trispline.Lattice.identity(bounds=((0, 0, 0), (1, 1, 1)), controls=(3, 3, 3), orders=(3, 3, 3)).control_points
    knots = [np.array([0, 0, 0, 1, 1, 1.0])] * 3
    L = trispline.Lattice(cp, (3, 3, 3), knots)  # no bounds: the points are parameters (u, v, w)
    uvw = np.random.default_rng(4).random((50, 3))
    assert np.abs(trispline.ffd_evaluate(L, uvw, backend="cpu_ref")[0] - uvw).max() < 1e-12
    assert [k.tolist() for k in L.knots] == [k.tolist() for k in knots]


@pytest.mark.parametrize("bad, match", [
    (np.zeros((10, 2)), r"#N×3"), (np.array([[0, 0, np.inf]]), "not finite"), (np.zeros((3, 3), bool), "dtype")])
def test_bad_points_raise_value_error(bad, match):
    L = trispline.Lattice.identity(bounds=(LO, HI))
    with pytest.raises(ValueError, match=match):
        trispline.ffd_evaluate(L, bad)


def test_bad_lattice_arguments_raise_value_error():
    with pytest.raises(ValueError, match=r"#nu×nv×nw×3"):
        trispline.Lattice(np.zeros((4, 4, 3)), (2, 2, 2))
    with pytest.raises(ValueError, match="order"):
        trispline.Lattice(np.zeros((3, 3, 3, 3)), (4, 2, 2))
    with pytest.raises(ValueError, match="backend"):
        trispline.ffd_evaluate(trispline.Lattice.identity(bounds=(LO, HI)), cloud(3), backend="glsl_compute")
    with pytest.raises(ValueError):  # cpu_fast does orders 2..4 only
        trispline.ffd_evaluate(trispline.Lattice.identity(bounds=(LO, HI), controls=(6, 6, 6), orders=(5, 5, 5)),
                               cloud(3))


def test_certify_identity_and_a_fold():
    L = trispline.Lattice.identity(bounds=(LO, HI), controls=(4, 4, 4), orders=(3, 3, 3))
    c = trispline.certify(L)
    assert c["verdict"] == "fold_free" and c["fold_free"] and c["cells"] == 8 and len(c["fold_cells"]) == 0
    cp = L.control_points
    cp[1:3, 1:3, 1:3, 0] = cp[1:3, 1:3, 1:3, 0][::-1]  # swap inner control points along x: the map turns over
    folded = trispline.certify(L.with_control_points(cp))
    assert folded["verdict"] == "fold" and not folded["fold_free"]
    assert folded["fold_cells"].shape[1] == 3 and (folded["fold_det"] <= 0).all()


def test_silhouettes_of_an_analytic_sphere():
    scene = trispline.Scene()
    entry = scene.run({"cmd": "volume.load", "analytic": "sphere", "name": "ball", "iso": 0.0})
    assert scene.volumes == ["ball"] and entry["cmd"] == "volume.load"
    eye = np.array([0.0, 0.0, 200.0])
    curves = trispline.silhouettes(scene, "ball", {"eye": eye, "target": (0, 0, 0), "up": (0, 1, 0)})
    assert len(curves) >= 1 and all(c.ndim == 2 and c.shape[1] == 3 for c in curves)
    p = np.vstack(curves)
    r = np.linalg.norm(p, axis=1)
    assert np.abs(r - 30.0).max() < 0.5  # D = 30 − |p|: the sphere of radius 30 mm
    # Perspective silhouette (Eq. 7.2): the gradient (radial) is orthogonal to the view ray p − eye.
    assert np.abs(((p / r[:, None]) * (p - eye)).sum(axis=1) / np.linalg.norm(p - eye, axis=1)).max() < 1e-3
    details = trispline.silhouettes(scene, "ball", {"eye": eye, "target": (0, 0, 0), "up": (0, 1, 0)}, details=True)
    assert details[0]["visible"].dtype == bool and len(details[0]["points"]) == len(details[0]["visible"])
    with pytest.raises(KeyError):
        trispline.silhouettes(scene, "nothing")
    with pytest.raises(ValueError):
        trispline.silhouettes(scene, "ball", {"eye": (0, 0, 0), "target": (0, 0, 0)})
