//! Binding a scene's stubs and clips to a built model's nodes (SPEC L6, L7), for the
//! workcell (SPEC W1), whichever shell runs it.

use crate::scene::{HoseEnd, LoadedScene};
use pliant_assembly::stub::PressFit;
use pliant_assembly::{ClipSite, StubSite};
use pliant_core::Model;

impl LoadedScene {
    /// The scene's stubs and clips, tied to `model`'s nodes (the model built from this
    /// scene). A stub must name its hose end and a clip its hose, unless the scene has
    /// only one hose.
    pub fn fastener_sites(&self, model: &Model) -> Result<(Vec<StubSite>, Vec<ClipSite>), String> {
        let only_hose = (model.hoses.len() == 1).then_some(0);
        let mut stubs = Vec::with_capacity(self.stubs.len());
        for s in &self.stubs {
            let Some(end) = s
                .hose_end
                .or(only_hose.map(|hose| HoseEnd { hose, at_end: true }))
            else {
                return Err(format!(
                    "stub '{}': name the hose end that goes onto it (`hose` and `end`)",
                    s.name
                ));
            };
            let info = &model.hoses[end.hose];
            let spec = &self.world.hoses[end.hose];
            let local = end.node(info.node_count);
            let inner = if end.at_end { local - 1 } else { local + 1 };
            let section = spec.sections[if spec.sections.len() == 1 { 0 } else { local }];
            let fit = PressFit::new(&s.spec, &section, &spec.material)
                .map_err(|e| format!("stub '{}': {e}", s.name))?;
            stubs.push(StubSite {
                name: s.name.clone(),
                fit,
                end_node: info.node(local),
                inner_node: info.node(inner),
            });
        }
        let mut clips = Vec::with_capacity(self.clips.len());
        for c in &self.clips {
            let Some(hose) = c.hose.or(only_hose) else {
                return Err(format!(
                    "clip '{}': name the hose that goes into it (`hose`)",
                    c.name
                ));
            };
            clips.push(ClipSite {
                name: c.name.clone(),
                spec: c.spec,
                hose,
            });
        }
        Ok((stubs, clips))
    }
}
