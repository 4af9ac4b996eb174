use super::*;

#[test]
fn cycles_are_found_with_their_members() {
    // 0 -> 1 -> 2 -> 0 is a cycle; 3 -> 4 is not; 5 <-> 6 is.
    let edges = [(0, 1), (1, 2), (2, 0), (3, 4), (2, 3), (5, 6), (6, 5)];
    let (cycles, members, examples) = find_cycles(&edges, 10);
    assert_eq!((cycles, members), (2, 5));
    let mut lens: Vec<usize> = examples.iter().map(Vec::len).collect();
    lens.sort_unstable();
    assert_eq!(lens, vec![2, 3]);
    for cycle in &examples {
        for k in 0..cycle.len() {
            let e = (cycle[k], cycle[(k + 1) % cycle.len()]);
            assert!(edges.contains(&e), "{e:?} in {cycle:?}");
        }
    }
    assert_eq!(find_cycles(&[(0, 1), (1, 2)], 10).0, 0);
}

#[test]
fn overlap_needs_shared_interior() {
    let p = |x: i32, y: i32| FixedPt::new(x * 256, y * 256);
    // Positive orientation: orient2d > 0.
    let a = [p(0, 0), p(10, 0), p(0, 10)];
    let a = if orient2d(a[0], a[1], a[2]) > 0 {
        a
    } else {
        [a[0], a[2], a[1]]
    };
    let shift = |t: [FixedPt; 3], dx: i32| t.map(|q| FixedPt::new(q.x + dx * 256, q.y));
    assert!(interiors_overlap(&a, &shift(a, 3)));
    // Sharing only the edge x + y = 10 with its mirror image.
    let b = [p(10, 0), p(0, 10), p(10, 10)];
    let b = if orient2d(b[0], b[1], b[2]) > 0 {
        b
    } else {
        [b[0], b[2], b[1]]
    };
    assert!(!interiors_overlap(&a, &b));
    assert!(overlap_point(&a, &shift(a, 3)).is_some());
}
