//! Binding a scene's stubs and clips to a built model's nodes (SPEC L6, L7), for the
//! workcell (SPEC W1), whichever shell runs it.

use crate::scene::LoadedScene;
use pliant_assembly::stub::PressFit;
use pliant_assembly::{ClipSite, StubSite};
use pliant_core::Model;

impl LoadedScene {
    /// The scene's stubs, connectors (as stub sites with their mating law) and clips, tied to `model`'s nodes (the model built from this
    /// scene; the loader has bound every stub to a hose end and every clip to a hose).
    pub fn fastener_sites(&self, model: &Model) -> Result<(Vec<StubSite>, Vec<ClipSite>), String> {
        let mut stubs = Vec::with_capacity(self.stubs.len() + self.connectors.len());
        for s in &self.stubs {
            let end = s.hose_end;
            let info = &model.hoses[end.hose];
            let spec = &self.world.hoses[end.hose];
            let local = end.node(info.node_count);
            let inner = if end.at_end { local - 1 } else { local + 1 };
            let section = *spec.node_section(local);
            let mut fit = PressFit::new(&s.spec, &section, &spec.material)
                .map_err(|e| format!("stub '{}': {e}", s.name))?;
            for &bead in &s.profile {
                fit = fit
                    .with_bead(bead)
                    .map_err(|e| format!("stub '{}': {e}", s.name))?;
            }
            stubs.push(StubSite {
                name: s.name.clone(),
                fit: fit.into(),
                end_node: info.node(local),
                inner_node: info.node(inner),
                part: s.part,
            });
        }
        // connectors after the stubs: the same state machine with the mating law
        for c in &self.connectors {
            let info = &model.hoses[c.hose_end.hose];
            let local = c.hose_end.node(info.node_count);
            let inner = if c.hose_end.at_end {
                local - 1
            } else {
                local + 1
            };
            stubs.push(StubSite {
                name: c.name.clone(),
                fit: c.mating.into(),
                end_node: info.node(local),
                inner_node: info.node(inner),
                part: c.part,
            });
        }
        let mut clips = Vec::with_capacity(self.clips.len());
        for c in &self.clips {
            clips.push(ClipSite {
                name: c.name.clone(),
                spec: c.spec,
                hose: c.hose,
                part: c.part,
                by_hand: c.by_hand,
            });
        }
        Ok((stubs, clips))
    }
}
