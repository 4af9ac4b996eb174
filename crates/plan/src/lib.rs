//! The hider registry, scene analysis and the planner (being assembled).
