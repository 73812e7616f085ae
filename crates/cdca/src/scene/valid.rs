//! [`Scene`]: a scene whose every value has been checked. The only way to
//! get one is through [`TryFrom<SceneFile>`] (parsing with
//! [`Scene::from_json`] and editing with [`Scene::edit`] or
//! [`Scene::with_param`] go through it), so the solver never checks a scene
//! again: a `Scene` that exists is valid.

use std::ops::Deref;

use serde::{Deserialize, Deserializer, Serialize, Serializer};

use super::criterion::Criterion;
use super::file::{CrackSpec, SceneFile};
use super::resume::Resume;
use crate::error::SceneError;

/// A valid scene (SPEC §10). Reads as its [`SceneFile`] (`scene.mesh.nx`,
/// through `Deref`); changes go through [`edit`](Self::edit), which checks
/// the result. Serialises exactly as the file.
#[derive(Clone, Debug, PartialEq)]
pub struct Scene {
    file: SceneFile,
    /// The file's criterion settings as the tagged type.
    criterion: Criterion,
}

impl TryFrom<SceneFile> for Scene {
    type Error = SceneError;

    /// Checks every value; the first problem found is the error, naming the
    /// field (a dotted JSON path) and the value.
    fn try_from(file: SceneFile) -> Result<Self, SceneError> {
        file.validate()?;
        let criterion = file.criterion.settings()?;
        Ok(Self { file, criterion })
    }
}

impl Deref for Scene {
    type Target = SceneFile;

    fn deref(&self) -> &SceneFile {
        &self.file
    }
}

impl Scene {
    /// Parses and checks a scene. Unknown fields, wrong types and invalid
    /// values are errors naming the field.
    pub fn from_json(text: &str) -> Result<Self, SceneError> {
        Self::try_from(SceneFile::from_json(text)?)
    }

    /// The scene with `change` applied, checked: the checked setter of any
    /// field. `self` is unchanged either way.
    pub fn edit(&self, change: impl FnOnce(&mut SceneFile)) -> Result<Self, SceneError> {
        let mut file = self.file.clone();
        change(&mut file);
        Self::try_from(file)
    }

    /// The file, to be edited freely (and checked again by `try_from`).
    pub fn into_file(self) -> SceneFile {
        self.file
    }

    /// The criterion with exactly the settings its kind reads.
    pub fn criterion_settings(&self) -> Criterion {
        self.criterion
    }

    /// Replaces the cracks by polylines the solver grew from valid ones
    /// (each point inside the specimen, segments of positive length), so the
    /// scene stays valid.
    pub(crate) fn set_grown_cracks(&mut self, cracks: Vec<CrackSpec>) {
        self.file.cracks = cracks;
    }

    /// Records where a growth run stands ([`Resume`], built by the solver
    /// from valid values).
    pub(crate) fn set_resume(&mut self, resume: Resume) {
        self.file.growth.resume = Some(resume);
    }
}

impl Serialize for Scene {
    fn serialize<S: Serializer>(&self, serializer: S) -> Result<S::Ok, S::Error> {
        self.file.serialize(serializer)
    }
}

impl<'de> Deserialize<'de> for Scene {
    /// Parses the file, then checks it ([`TryFrom<SceneFile>`]).
    fn deserialize<D: Deserializer<'de>>(deserializer: D) -> Result<Self, D::Error> {
        let file = SceneFile::deserialize(deserializer)?;
        Self::try_from(file).map_err(serde::de::Error::custom)
    }
}
