//! The immutable model of a scene: mesh, material, supports, and the
//! discretisation settings. Cracks are state, not model.

use crate::discretisation::boundary::constrained_dofs;
use crate::discretisation::material::Elastic;
use crate::discretisation::xfem::{Reuse, Xfem, XfemParams, prepare_cracks};
use crate::geometry::cracks::Crack;
use crate::geometry::mesh::Mesh;
use crate::scene::Scene;

/// Mesh, material and supports of a validated scene.
#[derive(Clone, Debug)]
pub struct Model {
    pub scene: Scene,
    pub mesh: Mesh,
    pub elastic: Elastic,
    /// `fixed[2n + c]`: standard DOF `c` of node `n` is constrained.
    pub fixed: Vec<bool>,
    pub params: XfemParams,
}

impl Model {
    /// Builds the model; the scene must already be validated.
    pub fn new(scene: Scene) -> Self {
        let mesh = Mesh::new(
            scene.specimen.width,
            scene.specimen.height,
            scene.mesh.nx,
            scene.mesh.ny,
        );
        let elastic = Elastic::new(&scene.material);
        let fixed = constrained_dofs(&mesh, &scene.boundary);
        let params = XfemParams {
            enrichment_radius: scene.mesh.enrichment_radius.unwrap_or(2.5),
            ..XfemParams::default()
        };
        Self {
            scene,
            mesh,
            elastic,
            fixed,
            params,
        }
    }

    /// The scene's cracks, tips classified.
    pub fn initial_cracks(&self) -> Vec<Crack> {
        let h = self.mesh.h();
        let cracks = self
            .scene
            .cracks
            .iter()
            .map(|c| Crack::from_spec(c, h, self.elastic.young))
            .collect();
        prepare_cracks(cracks, &self.mesh)
    }

    /// The discretisation of a crack configuration.
    pub fn discretise(&self, cracks: Vec<Crack>) -> Xfem {
        let mut x = self.rediscretise(cracks, None);
        x.integrate(usize::MAX);
        x
    }

    /// The same, reusing what did not change from a previous one; the
    /// stiffness of the elements that changed is left to
    /// [`Xfem::integrate`] (see [`Xfem::build`]).
    pub fn rediscretise(&self, cracks: Vec<Crack>, reuse: Option<&Reuse>) -> Xfem {
        Xfem::build(
            self.mesh.clone(),
            self.elastic.clone(),
            self.scene.specimen.thickness,
            cracks,
            &self.fixed,
            self.params,
            reuse,
        )
    }
}
