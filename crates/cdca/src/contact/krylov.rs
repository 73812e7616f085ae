//! GMRES for the Newton steps' slip systems
//! ([`newton_step`](crate::contact::newton::newton_step)), resumable: a
//! system solved to the loose tolerance and then, where its step ends the
//! iteration, to the tight one goes on from the loose solve's Krylov
//! space instead of building it again (a re-solve from `e = 0` repeats
//! the loose solve's iterations exactly before it goes further).
//!
//! GMRES (Saad & Schultz 1986; no restart, modified Gram–Schmidt, Givens
//! rotations) for `S e = b`: after `k` iterations the Arnoldi relation
//! `S V_k = V_{k+1} H̄_k` gives the residual `‖β e₁ − H̄_k y‖` of every
//! `e = V_k y` from the rotated right-hand side alone, and the solution of
//! the least-squares problem by back substitution on the rotated `H̄_k`.
//! Going on from `k` adds columns to `V` and `H̄` without touching the
//! earlier ones, so the iterates are those of one solve to the tighter
//! tolerance.

/// A GMRES solve of `op(e) = b` in progress.
pub(crate) struct Gmres {
    /// `‖b‖`.
    beta: f64,
    /// The orthonormal Krylov basis `v_1 … v_{k+1}`.
    basis: Vec<Vec<f64>>,
    /// The columns of `H̄`, rotated (upper triangular).
    h: Vec<Vec<f64>>,
    /// The Givens rotations' cosines and sines.
    cs: Vec<f64>,
    sn: Vec<f64>,
    /// The rotated right-hand side `β Qᵀ e₁`.
    rhs: Vec<f64>,
    /// The Krylov space is invariant: the last solution is exact.
    exhausted: bool,
}

/// A solution of [`Gmres::solve`]: `e`, its relative residual and the
/// applications of `op` the call took.
pub(crate) struct Solved {
    pub e: Vec<f64>,
    pub residual: f64,
    pub iterations: usize,
}

impl Gmres {
    /// A solve of `op(e) = b` from `e = 0`.
    pub fn new(b: &[f64]) -> Self {
        let beta = norm(b);
        Self {
            beta,
            basis: vec![b.iter().map(|a| a / beta).collect()],
            h: Vec::new(),
            cs: Vec::new(),
            sn: Vec::new(),
            rhs: vec![beta],
            exhausted: beta == 0.0,
        }
    }

    /// The relative residual of the current iterate (0 for `b = 0`).
    fn residual(&self) -> f64 {
        if self.beta == 0.0 {
            0.0
        } else {
            self.rhs[self.h.len()].abs() / self.beta
        }
    }

    /// Iterates until the relative residual is at most `tolerance`, to at
    /// most `max` iterations in all (those of earlier calls included);
    /// `None` when `op` fails, the tolerance is not met or the solution is
    /// not finite. The iterate after an earlier call's is the same whether
    /// or not that call stopped in between.
    pub fn solve(
        &mut self,
        op: &mut dyn FnMut(&[f64]) -> Option<Vec<f64>>,
        max: usize,
        tolerance: f64,
    ) -> Option<Solved> {
        let mut iterations = 0;
        while !self.exhausted && self.residual() > tolerance {
            if self.h.len() >= max {
                return None;
            }
            self.iterate(&mut *op)?;
            iterations += 1;
        }
        let e = self.solution();
        e.iter().all(|v| v.is_finite()).then(|| Solved {
            e,
            residual: self.residual(),
            iterations,
        })
    }

    /// One Arnoldi step and its rotation.
    fn iterate(&mut self, op: &mut dyn FnMut(&[f64]) -> Option<Vec<f64>>) -> Option<()> {
        let k = self.h.len();
        let mut w = op(&self.basis[k])?;
        let mut col = Vec::with_capacity(k + 2);
        for v in &self.basis {
            let hk: f64 = v.iter().zip(&w).map(|(a, b)| a * b).sum();
            for (wi, vi) in w.iter_mut().zip(v) {
                *wi -= hk * vi;
            }
            col.push(hk);
        }
        let next = norm(&w);
        col.push(next);
        for j in 0..k {
            let (a, b) = (col[j], col[j + 1]);
            col[j] = self.cs[j] * a + self.sn[j] * b;
            col[j + 1] = -self.sn[j] * a + self.cs[j] * b;
        }
        let r = col[k].hypot(col[k + 1]);
        let (c, s) = if r == 0.0 {
            (1.0, 0.0)
        } else {
            (col[k] / r, col[k + 1] / r)
        };
        col[k] = r;
        self.cs.push(c);
        self.sn.push(s);
        self.rhs.push(-s * self.rhs[k]);
        self.rhs[k] *= c;
        col.truncate(k + 1);
        self.h.push(col);
        if next == 0.0 {
            self.exhausted = true;
        } else {
            self.basis.push(w.iter().map(|a| a / next).collect());
        }
        Some(())
    }

    /// `e = V_k y` with `y` from back substitution on the rotated `H̄_k`.
    fn solution(&self) -> Vec<f64> {
        let k = self.h.len();
        let mut y = vec![0.0; k];
        for i in (0..k).rev() {
            let s: f64 = (i + 1..k).map(|j| self.h[j][i] * y[j]).sum();
            y[i] = (self.rhs[i] - s) / self.h[i][i];
        }
        let mut e = vec![0.0; self.basis[0].len()];
        for (yi, v) in y.iter().zip(&self.basis) {
            for (ei, vi) in e.iter_mut().zip(v) {
                *ei += yi * vi;
            }
        }
        e
    }
}

fn norm(a: &[f64]) -> f64 {
    a.iter().map(|v| v * v).sum::<f64>().sqrt()
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A non-symmetric 4 × 4 system `(I + M) e = b` (M with entries ±0.3).
    fn system() -> (nalgebra::DMatrix<f64>, nalgebra::DVector<f64>) {
        let m = nalgebra::DMatrix::from_row_slice(
            4,
            4,
            &[
                1.0, 0.3, -0.2, 0.0, //
                -0.3, 1.2, 0.1, 0.25, //
                0.05, -0.1, 0.9, 0.3, //
                0.2, 0.0, -0.3, 1.1,
            ],
        );
        (m, nalgebra::DVector::from_vec(vec![1.0, -2.0, 0.5, 3.0]))
    }

    /// `v ↦ m v`, as GMRES applies its operator.
    fn product(m: &nalgebra::DMatrix<f64>) -> impl FnMut(&[f64]) -> Option<Vec<f64>> + '_ {
        move |v| {
            Some(
                (m * nalgebra::DVector::from_column_slice(v))
                    .as_slice()
                    .to_vec(),
            )
        }
    }

    /// GMRES on the system against its solution by LU: equal to 1e-12, in
    /// at most 4 iterations (the dimension).
    #[test]
    fn gmres_solves_a_small_nonsymmetric_system() {
        let (m, b) = system();
        let exact = m.clone().lu().solve(&b).expect("regular");
        let mut op = product(&m);
        let s = Gmres::new(b.as_slice())
            .solve(&mut op, 10, 1e-11)
            .expect("converges");
        assert!(s.iterations <= 4, "{} iterations", s.iterations);
        assert!(s.residual <= 1e-11);
        for (a, b) in s.e.iter().zip(exact.iter()) {
            assert!(
                (a - b).abs() <= 1e-12 * exact.amax(),
                "{:?} vs {exact}",
                s.e
            );
        }
    }

    /// A solve to 1e-2 taken on to 1e-11 gives the solve straight to 1e-11
    /// bit for bit, and its iterations add up to that solve's.
    #[test]
    fn a_loose_solve_taken_on_is_the_tight_solve() {
        let (m, b) = system();
        let mut op = product(&m);
        let tight = Gmres::new(b.as_slice())
            .solve(&mut op, 10, 1e-11)
            .expect("converges");
        let mut resumed = Gmres::new(b.as_slice());
        let loose = resumed.solve(&mut op, 10, 1e-2).expect("converges");
        assert!(loose.residual <= 1e-2 && loose.iterations < tight.iterations);
        let on = resumed.solve(&mut op, 10, 1e-11).expect("converges");
        assert_eq!(loose.iterations + on.iterations, tight.iterations);
        assert_eq!(on.e, tight.e);
        assert_eq!(on.residual, tight.residual);
    }
}
