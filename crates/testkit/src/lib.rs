//! Test set-up shared by the hider workspace (being assembled).
