//! The scene at the worst bend of a few hoses, for the report's pictures (SPEC V7), in
//! bounded memory: a copy of every node is kept for at most
//! [`MAX_SCENE_PICTURES`] hoses — those whose bend radius fell furthest below their
//! limit — instead of one copy per hose (memory and report size grew with hoses × nodes:
//! a 1 000 × 20 study wrote a 2.3 GB `report.json`). The copies are shared (`Arc`), so a
//! run summary taken while the study goes on (a live snapshot) does not copy them.

use glam::DVec3;
use pliant_core::kinematics::Pose;
use std::sync::Arc;

/// Most hoses whose scene at their worst bend is kept for the report.
pub const MAX_SCENE_PICTURES: usize = 4;

/// Every node of the scene at the instant of one hose's smallest bend radius below its
/// limit.
#[derive(Clone, Debug, PartialEq)]
pub struct ScenePicture {
    /// The hose whose worst bend this is.
    pub hose: usize,
    /// Its allowed bend radius over its smallest one (> 1: how far it is violated).
    pub severity: f64,
    /// Every node of the scene (all hoses) at that instant \[m\].
    pub positions: Arc<Vec<[f64; 3]>>,
    /// When \[s\].
    pub time: f64,
    /// Every part's pose then (the identity for a part that stands still), so that the
    /// picture draws a moving part where it was.
    pub part_poses: Arc<Vec<Pose>>,
}

/// The pictures of at most [`MAX_SCENE_PICTURES`] hoses, the most severe kept.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct ScenePictures {
    pictures: Vec<ScenePicture>,
}

impl ScenePictures {
    /// Notes hose `hose`'s new smallest bend radius, `severity` times below its limit, at
    /// `time`, when the nodes were at `x` and the parts at `poses`: kept if the hose has a
    /// picture already or is among the most severe.
    /// Allocates only while fewer than [`MAX_SCENE_PICTURES`] pictures are held (and
    /// when a summary still shares the copy being replaced).
    pub fn note(
        &mut self,
        hose: usize,
        severity: f64,
        time: f64,
        x: &[DVec3],
        poses: impl Iterator<Item = Pose>,
    ) {
        let slot = match self.pictures.iter().position(|p| p.hose == hose) {
            Some(k) => k,
            None if self.pictures.len() < MAX_SCENE_PICTURES => {
                self.pictures.push(ScenePicture {
                    hose,
                    severity,
                    positions: Arc::new(Vec::with_capacity(x.len())),
                    time,
                    part_poses: Arc::default(),
                });
                self.pictures.len() - 1
            }
            None => {
                let (k, least) = self
                    .pictures
                    .iter()
                    .enumerate()
                    .min_by(|a, b| a.1.severity.total_cmp(&b.1.severity))
                    .expect("MAX_SCENE_PICTURES > 0");
                if !(severity > least.severity) {
                    return;
                }
                k
            }
        };
        let p = &mut self.pictures[slot];
        p.hose = hose;
        p.severity = severity;
        let positions = Arc::make_mut(&mut p.positions);
        positions.clear();
        positions.extend(x.iter().map(|p| p.to_array()));
        p.time = time;
        let part_poses = Arc::make_mut(&mut p.part_poses);
        part_poses.clear();
        part_poses.extend(poses);
    }

    /// The picture of hose `hose`, if it is kept.
    pub fn of(&self, hose: usize) -> Option<&ScenePicture> {
        self.pictures.iter().find(|p| p.hose == hose)
    }

    /// The pictures kept.
    pub fn all(&self) -> &[ScenePicture] {
        &self.pictures
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn only_the_most_severe_hoses_keep_a_copy_of_the_scene() {
        let x = vec![DVec3::ONE; 10];
        let mut pictures = ScenePictures::default();
        for hose in 0..100 {
            pictures.note(hose, 1.0 + hose as f64, 0.0, &x, std::iter::empty());
        }
        assert_eq!(pictures.all().len(), MAX_SCENE_PICTURES);
        for hose in 100 - MAX_SCENE_PICTURES..100 {
            assert!(pictures.of(hose).is_some(), "hose {hose}");
        }
        // a milder one does not displace them; a worse bend of a kept hose updates it
        pictures.note(3, 1.5, 0.0, &x, std::iter::empty());
        assert!(pictures.of(3).is_none());
        pictures.note(99, 500.0, 0.0, &x, std::iter::empty());
        assert_eq!(pictures.of(99).unwrap().severity, 500.0);
        assert_eq!(pictures.all().len(), MAX_SCENE_PICTURES);
    }
}
