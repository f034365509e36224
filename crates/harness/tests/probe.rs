use pliant_harness::geometry::SegmentCurve;
#[test]
fn probe() {
    let dir = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../../data/harness");
    for e in std::fs::read_dir(&dir).unwrap() {
        let p = e.unwrap().path();
        if p.extension().map_or(true, |x| x != "kbl") { continue; }
        let h = pliant_harness::read_kbl(&p).unwrap();
        let at = h.segments_at_nodes();
        let deg: Vec<usize> = at.iter().map(|v| v.len()).collect();
        println!("{}: nodes {} segs {} wires {} parts {} fix {} prot {} conn {} L {:.3} deg>=3 {} deg>=2 {} maxdeg {:?} skipped {} warnings {:?}",
          h.source, h.nodes.len(), h.segments.len(), h.wires.len(), h.wire_parts.len(), h.fixings.len(), h.protections.len(), h.connectors.len(), h.total_virtual_length(),
          deg.iter().filter(|&&d| d>=3).count(), deg.iter().filter(|&&d| d>=2).count(), deg.iter().max(), h.skipped.len(), h.warnings);
        for s in h.skipped.iter().take(5) { println!("  skip {:?}", s); }
        let mut worst_end: f64 = 0.0; let mut worst_len: f64 = 0.0;
        for s in &h.segments {
            let c = SegmentCurve::of(&h, s);
            let rel = s.virtual_length.map(|v| (c.length - v).abs() / v).unwrap_or(0.0);
            worst_end = worst_end.max(c.start_error).max(c.end_error);
            worst_len = worst_len.max(rel);
            if c.trimmed || rel > 1e-3 || c.start_error.max(c.end_error) > 1e-6 || s.wires.is_empty() {
                println!("  {} {:?} trimmed {} rev {} err {:.3e} {:.3e} len {:.4} vl {:?} rel {:.2e} wires {}", s.kbl_id, s.name, c.trimmed, c.u_end < c.u_start, c.start_error*1e3, c.end_error*1e3, c.length, s.virtual_length, rel, s.wires.len());
            }
        }
        println!("  worst end {:.3e} mm worst len rel {:.3e}", worst_end*1e3, worst_len);
        let maxw = h.segments.iter().map(|s| s.wires.len()).max();
        println!("  max wires/segment {:?}; conn without node {}", maxw, h.connectors.iter().filter(|c| c.node.is_none()).count());
    }
}
