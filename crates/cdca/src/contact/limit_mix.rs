//! The outer loop's update of the friction limits (SPEC §5): Anderson
//! mixing of the fixed-point map `τ ↦ G(τ) = μ|p_N(g(τ))| + c_c`, where
//! `g(τ)` solves the inner (Tresca) problem with the limits `τ` held fixed,
//! kept non-negative by restarting instead of clamping.

use nalgebra::{DMatrix, DVector};

/// Pairs kept for the Anderson mix of the friction limits (measured on the
/// issue-17 growth harness: without the mix 29% more linear solves, and
/// the default scene at μ = 0.6 stopped `not_converged`).
pub const ANDERSON_DEPTH: usize = 5;

/// Anderson mixing of a fixed-point map `τ ↦ G(τ)` over the last
/// [`ANDERSON_DEPTH`] steps.
#[derive(Default)]
pub struct LimitMix {
    /// `(τ, G(τ))`, oldest first.
    pairs: Vec<(Vec<f64>, Vec<f64>)>,
}

impl LimitMix {
    /// The limits to hold next, after the inner problem of `limits` gave
    /// `target = G(limits)`: the Anderson mix, with negative values set to
    /// zero, or `target` itself (the plain step) before there are two
    /// pairs, and whenever the mix would take a limit below zero that the
    /// plain step raises (`target > 0`). There the history does not
    /// support the extrapolation: a point whose friction presses it shut,
    /// as at a kink in a crack, has `G(τ) − τ` about constant, and cut back
    /// to zero the mix kept that point slipping free, forever. The mixing
    /// then restarts from the plain step.
    pub fn next(&mut self, limits: &[f64], target: Vec<f64>) -> Vec<f64> {
        match self.push(limits, &target) {
            Some(m) if m.iter().zip(&target).all(|(v, t)| *v >= 0.0 || *t <= 0.0) => {
                m.into_iter().map(|v| v.max(0.0)).collect()
            }
            Some(_) => {
                self.pairs.clear();
                target
            }
            None => target,
        }
    }

    /// Adds `(τ, G(τ))`; returns the mixed iterate once there are two
    /// pairs: `G − Σ γ_j ΔG_j` with `γ` minimising
    /// `‖(G − τ) − Σ γ_j Δ(G − τ)_j‖`.
    fn push(&mut self, tau: &[f64], g: &[f64]) -> Option<Vec<f64>> {
        self.pairs.push((tau.to_vec(), g.to_vec()));
        if self.pairs.len() > ANDERSON_DEPTH + 1 {
            self.pairs.remove(0);
        }
        let k = self.pairs.len();
        if k < 2 {
            return None;
        }
        let f = |j: usize, i: usize| self.pairs[j].1[i] - self.pairs[j].0[i];
        let df = DMatrix::from_fn(g.len(), k - 1, |i, j| f(j + 1, i) - f(j, i));
        let fk = DVector::from_fn(g.len(), |i, _| f(k - 1, i));
        let svd = df.svd(true, true);
        let largest = svd.singular_values.max();
        if largest <= 0.0 {
            return None;
        }
        let gamma = svd.solve(&fk, 1e-12 * largest).ok()?;
        let mut mixed = g.to_vec();
        for (j, w) in self.pairs.windows(2).enumerate() {
            for (v, (a, b)) in mixed.iter_mut().zip(w[1].1.iter().zip(&w[0].1)) {
                *v -= gamma[j] * (a - b);
            }
        }
        mixed.iter().all(|v| v.is_finite()).then_some(mixed)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// On an affine map `G(τ) = A τ + b` of n unknowns, Anderson mixing
    /// with n + 1 pairs is exact: its step lands on the fixed point
    /// `(I − A)⁻¹ b`, here at the third limits held (to 1e-12), where three
    /// plain steps (spectral radius 0.84) leave 75% of the first error.
    #[test]
    fn the_mix_finds_the_fixed_point_of_an_affine_map() {
        let g = |t: &[f64]| {
            vec![
                0.9 * t[0] + 0.1 * t[1] + 1.0,
                -0.2 * t[0] + 0.5 * t[1] + 3.0,
            ]
        };
        // (I − A)⁻¹ = [[0.5, 0.1], [−0.2, 0.1]] / 0.07
        let exact = [(0.5 + 0.1 * 3.0) / 0.07, (-0.2 + 0.1 * 3.0) / 0.07];
        let error = |t: &[f64]| (t[0] - exact[0]).hypot(t[1] - exact[1]);
        let (mut mixed, mut plain) = (vec![1.0, 1.0], vec![1.0, 1.0]);
        let mut mix = LimitMix::default();
        for _ in 0..3 {
            let target = g(&mixed);
            mixed = mix.next(&mixed, target);
            plain = g(&plain);
        }
        assert!(error(&mixed) < 1e-12 * exact[0], "{mixed:?} vs {exact:?}");
        let share = error(&plain) / error(&[1.0, 1.0]);
        assert!((share - 0.7488).abs() < 1e-4, "{share}");
    }

    /// A limit whose friction presses it shut (`G(τ) = 1.01 τ + 0.3`:
    /// raising it raises the normal pressure by more) is extrapolated by
    /// the mix to its fixed point at τ = −30: the mix restarts instead, and
    /// every limit held is the plain step, above zero.
    #[test]
    fn a_limit_the_plain_step_raises_is_not_mixed_below_zero() {
        let g = |t: &[f64]| vec![1.01 * t[0] + 0.3];
        let mut mix = LimitMix::default();
        let mut tau = vec![0.2];
        for _ in 0..6 {
            let target = g(&tau);
            let next = mix.next(&tau, target.clone());
            assert_eq!(next, target);
            tau = next;
        }
        assert!(tau[0] > 0.2 + 6.0 * 0.3, "{tau:?}");
    }
}
