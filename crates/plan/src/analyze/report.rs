//! The human-readable effects report (`hider analyze`).

use std::fmt;

use super::effects::{Effects, Evidence};

impl Evidence {
    /// `yes` / `no`, with `?` when the search did not finish.
    pub fn verdict(&self) -> &'static str {
        match (self.present, self.certain) {
            (true, true) => "yes",
            (true, false) => "yes?",
            (false, _) => "no",
        }
    }
}

fn line(f: &mut fmt::Formatter<'_>, name: &str, e: &Evidence) -> fmt::Result {
    write!(f, "  {name:<18} {:<4} {}", e.verdict(), e.detail)?;
    if !e.examples.is_empty() {
        let groups: Vec<String> = e
            .examples
            .iter()
            .map(|g| {
                let ids: Vec<String> = g.iter().map(u32::to_string).collect();
                if g.len() == 1 {
                    ids[0].clone()
                } else {
                    format!("({})", ids.join(" "))
                }
            })
            .collect();
        write!(f, "; e.g. {}", groups.join(", "))?;
    }
    writeln!(f)
}

impl fmt::Display for Effects {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        writeln!(
            f,
            "{} triangles, {} on screen; deepest/near {:.3e}; analysed in {:.1} ms \
             (prepare {:.1}, intersections {:.1}, overlaps {:.1}); pairs listed {} / tested {} \
             (intersections), {} / {} (overlaps)",
            self.triangles,
            self.on_screen,
            self.depth_ratio,
            self.times.total_ms,
            self.times.prepare_ms,
            self.times.intersections_ms,
            self.times.overlaps_ms,
            self.work.intersection_candidates,
            self.work.intersection_tests,
            self.work.overlap_candidates,
            self.work.overlap_tests
        )?;
        line(f, "transparency", &self.transparency)?;
        line(f, "textures", &self.textures)?;
        line(f, "lighting", &self.lighting)?;
        line(f, "anti-aliasing", &self.antialiasing)?;
        line(f, "intersections", &self.intersections)?;
        line(f, "cyclic overlap", &self.cyclic_overlap)?;
        line(f, "back faces", &self.back_faces)?;
        line(f, "coplanar overlaps", &self.coplanar_overlaps)?;
        line(f, "naive order wrong", &self.naive_order_violations)?;
        writeln!(
            f,
            "  ordered polygons   {}",
            if self.ordered_polygons {
                "asked"
            } else {
                "not asked"
            }
        )?;
        write!(
            f,
            "  back-face culling  {}",
            if self.cull_back_faces_exact {
                "exact here (saves work)"
            } else {
                "not applied"
            }
        )
    }
}
