//! Undo and Redo on the app: the present as an undo entry, and an entry
//! brought back (the scene, its title, a kept run, a kept study). Open,
//! Reset, a Solve after growth, an edit after a run and a new study each
//! record what they replace, so one Undo brings it back as it was.

use crate::app::WorkbenchApp;
use crate::run::runner::KeptRun;
use crate::state::undo::Entry;
use crate::state::view::Message;

impl WorkbenchApp {
    /// The present as an undo entry: the scene and its title; with `run`,
    /// the run on screen, moved out ([`Runner::take_run`]); with `study`,
    /// the study in the Study tab, moved out (stopped if it runs).
    ///
    /// [`Runner::take_run`]: crate::run::runner::Runner::take_run
    pub(crate) fn present(&mut self, run: bool, study: bool) -> Entry {
        let study = if study { self.study.take() } else { None };
        Entry {
            scene: self.scene.clone(),
            source: self.scene_source.clone(),
            opened: self.opened_scene.clone(),
            run: if run { self.runner.take_run() } else { None }.map(Box::new),
            study: study.map(|mut s| {
                s.cancel();
                Box::new(s)
            }),
        }
    }

    /// Records the present before an action that replaces the run on
    /// screen (`run`) or the finished study (`study`): one undo step.
    pub(crate) fn record_replacing(&mut self, run: bool, study: bool) {
        let study = study
            && self
                .study
                .as_ref()
                .is_some_and(crate::study::Study::finished);
        let present = self.present(run, study);
        self.undo.record(|| present, false);
    }

    /// Records `run` (a run an action took off the screen), if any, with
    /// the present scene: one undo step.
    pub(crate) fn record_run(&mut self, run: Option<KeptRun>) {
        if let Some(run) = run {
            let mut present = self.present(false, false);
            present.run = Some(Box::new(run));
            self.undo.record(|| present, false);
        }
    }

    pub(crate) fn undo(&mut self) {
        if let Some(entry) = self.undo.undo() {
            let present = self.bring_back(entry);
            self.undo.undone(present);
        }
    }

    pub(crate) fn redo(&mut self) {
        if let Some(entry) = self.undo.redo() {
            let present = self.bring_back(entry);
            self.undo.redone(present);
        }
    }

    /// Makes `entry` the present, and returns the present it replaces
    /// (with its run whenever the run goes, and its study when the entry
    /// brings one back).
    fn bring_back(&mut self, entry: Entry) -> Entry {
        let changes_scene = entry.scene != self.scene;
        let present = self.present(entry.run.is_some() || changes_scene, entry.study.is_some());
        if entry.source != self.scene_source || entry.opened != self.opened_scene {
            self.canvas.fit_requested = true;
        }
        self.scene_source = entry.source;
        self.opened_scene = entry.opened;
        if let Some(study) = entry.study {
            self.study = Some(*study);
        }
        self.scene = entry.scene;
        match entry.run {
            Some(run) => {
                let steps = run.steps();
                self.replay_step = None;
                self.race = None;
                self.selected_tip = None;
                self.tip_curve = None;
                self.editor = crate::state::edit::Editor::default();
                self.runner.restore_run(*run, &self.scene);
                self.message = Some(Message::Info(format!(
                    "Back to the run after growth step {steps}, as it was."
                )));
            }
            None if changes_scene => self.scene_changed(false),
            None => {}
        }
        present
    }
}
