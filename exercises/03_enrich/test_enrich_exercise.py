"""Exercise 03, enrichment: make these pass in order (``pytest exercises/03_enrich``)."""
import numpy as np

ASKED = ("heaviside", "enriched_value", "jump")
LIBRARY = ("skxfem.enrich",)   # it holds the answer: write your own

RNG = np.random.default_rng(3)


def test_01_heaviside_is_plus_or_minus_one(impl):
    for psi, want in ((-0.2, -1.0), (1e-9, 1.0), (3.0, 1.0), (-1e-9, -1.0)):
        got = float(np.asarray(impl.heaviside(np.array(psi))))
        assert got == want, (
            f"heaviside({psi}) is {got:g}; "
            + ("in Ω⁻ (ψ < 0) H must be -1" if psi < 0 else "in Ω⁺ (ψ > 0) H must be +1")
            + (" (H = ±1, not 0/1)" if got == 0.0 else ""))


def test_02_heaviside_on_arrays(impl):
    psi = np.array([[-1.0, 2.0], [0.5, -0.1]])
    got = np.asarray(impl.heaviside(psi))
    assert got.shape == psi.shape, f"heaviside of a {psi.shape} array must have shape {psi.shape}"
    assert np.array_equal(got, np.sign(psi)), (
        f"heaviside({psi.tolist()}) should be {np.sign(psi).tolist()}, got {got.tolist()}")


def test_03_the_field_at_a_node_is_its_standard_dof(impl):
    a, b = np.array([2.0, 3.0, 5.0]), np.array([7.0, 11.0, 13.0])
    H_nodes = np.array([-1.0, 1.0, 1.0])
    for i in range(3):
        phi = np.eye(3)[i]                     # at node i, φ_j = δ_ij
        got = impl.enriched_value(phi, a, b, H_nodes[i], H_nodes)
        assert abs(got - a[i]) < 1e-12, (
            f"at node {i} (φ = {phi.tolist()}, on its own side H = H_{i} = {H_nodes[i]:g}) "
            f"u_h should be a_{i} = {a[i]:g}, got {got:g}: with the shift b_j φ_j (H - H_j) the "
            f"enrichment vanishes at the nodes, so a is the nodal displacement")


def test_04_the_field_on_each_side(impl):
    phi = np.array([0.2, 0.3, 0.5])
    a, b = RNG.normal(size=3), RNG.normal(size=3)
    H_nodes = np.array([-1.0, -1.0, 1.0])
    for H in (-1.0, 1.0):
        want = phi @ a + phi @ (b * (H - H_nodes))
        got = impl.enriched_value(phi, a, b, H, H_nodes)
        assert abs(got - want) < 1e-12, (
            f"u_h = Σ a_i φ_i + Σ b_i φ_i (H - H_i) at φ = {phi.tolist()} on the side H = "
            f"{H:g} is {want:.6g}, got {got:.6g}"
            + (" (did you forget the shift - H_i?)"
               if abs(got - (phi @ a + H * phi @ b)) < 1e-12 else ""))


def test_05_jump_known_value(impl):
    got = impl.jump(np.array([0.25, 0.75]), np.array([1.0, 2.0]))
    assert abs(got + 3.5) < 1e-12, (
        f"jump(φ = (0.25, 0.75), b = (1, 2)) should be -2 (0.25·1 + 0.75·2) = -3.5, got "
        f"{got:g}" + (": [[u]] = u⁻ - u⁺, the value below Γ minus the value above"
                      if abs(got - 3.5) < 1e-12 else ""))


def test_06_jump_is_the_difference_of_the_two_sides(impl):
    for _ in range(5):
        phi = RNG.random(4)
        phi /= phi.sum()
        a, b = RNG.normal(size=4), RNG.normal(size=4)
        H_nodes = np.array([-1.0, 1.0, 1.0, -1.0])
        minus = impl.enriched_value(phi, a, b, -1.0, H_nodes)
        plus = impl.enriched_value(phi, a, b, 1.0, H_nodes)
        got = impl.jump(phi, b)
        assert abs(got - (minus - plus)) < 1e-12, (
            f"[[u]] = u⁻ - u⁺ = {minus:.6g} - {plus:.6g} = {minus - plus:.6g} from your "
            f"enriched_value, but jump gives {got:.6g}")
