use super::*;

fn p(x: i32, y: i32) -> FixedPt {
    FixedPt::new(x, y)
}

/// Whether two closed sectors share a direction, by sampling each
/// sector's directions finely (the brute-force reference).
fn meet(apex: FixedPt, a: Sector<FixedPt>, b: Sector<FixedPt>) -> bool {
    let within = |s: Sector<FixedPt>, d: FixedPt| {
        // Angle from start to d (ccw) at most angle from start to end.
        let ang = |q: FixedPt| {
            let (x, y) = (f64::from(q.x - apex.x), f64::from(q.y - apex.y));
            y.atan2(x).rem_euclid(std::f64::consts::TAU)
        };
        let t = |q: FixedPt| (ang(q) - ang(s.start)).rem_euclid(std::f64::consts::TAU);
        let (td, te) = (t(d), t(s.end));
        td <= te + 1e-12 || td >= std::f64::consts::TAU - 1e-12
    };
    within(a, b.start) || within(b, a.start)
}

#[test]
fn fan_sectors_meet_only_their_neighbours() {
    let apex = p(0, 0);
    let n = 64;
    let rim: Vec<FixedPt> = (0..n)
        .map(|k| {
            let a = std::f64::consts::TAU * f64::from(k) / f64::from(n);
            p(
                (1000.0 * a.cos()).round() as i32,
                (1000.0 * a.sin()).round() as i32,
            )
        })
        .collect();
    let sectors: Vec<_> = (0..n as usize)
        .map(|k| Sector::around(apex, rim[k], rim[(k + 1) % n as usize]).unwrap())
        .collect();
    let pairs = sector_pairs(apex, &sectors, |_| true);
    // Each triangle meets its two neighbours along the shared edge.
    assert_eq!(pairs.len(), n as usize);
    for (i, j) in pairs {
        let d = j - i;
        assert!(d == 1 || d == n as u32 - 1, "({i}, {j})");
    }
}

#[test]
fn pairs_match_brute_force_on_random_sectors() {
    let mut seed = 12345u64;
    let mut rnd = |m: i32| {
        seed = seed
            .wrapping_mul(6364136223846793005)
            .wrapping_add(1442695040888963407);
        ((seed >> 33) as i64 % i64::from(2 * m + 1)) as i32 - m
    };
    for round in 0..200 {
        let apex = p(rnd(3), rnd(3));
        let n = 2 + round % 12;
        // Small coordinates: many equal and opposite directions.
        let sectors: Vec<_> = (0..n)
            .filter_map(|_| Sector::around(apex, p(rnd(4), rnd(4)), p(rnd(4), rnd(4))))
            .collect();
        let query = |i: usize| !(i + round).is_multiple_of(3);
        let got = sector_pairs(apex, &sectors, query);
        let mut want = Vec::new();
        for i in 0..sectors.len() {
            for j in i + 1..sectors.len() {
                if (query(i) || query(j)) && meet(apex, sectors[i], sectors[j]) {
                    want.push((i as u32, j as u32));
                }
            }
        }
        assert_eq!(got, want, "round {round}: {sectors:?}");
    }
}

#[test]
fn stars_group_the_triangles_around_a_hub() {
    // A fan of five around corner key 0, plus a lone triangle and a
    // degenerate one at the hub.
    let tris = [
        [0, 1, 2],
        [0, 2, 3],
        [3, 0, 4],
        [0, 4, 5],
        [5, 6, 0],
        [7, 8, 9],
        [0, 0, 1],
    ];
    let stars = Stars::new(tris.len(), |k| Some(tris[k]), 5);
    assert_eq!(stars.len(), 1);
    assert_eq!(stars.members(0), &[(0, 0), (1, 0), (2, 1), (3, 0), (4, 2)]);
    assert_eq!(stars.group(5), NO_STAR);
    assert_eq!(stars.group(6), NO_STAR);
    assert!(stars.share(0, 4) && !stars.share(0, 5) && !stars.share(0, 6));
    assert!(Stars::new(tris.len(), |k| Some(tris[k]), 6).is_empty());
    assert!(Stars::default().is_empty());
    // One star of five: 12 pairs inside, more than 7 triangles.
    assert!(stars.pay_for(7) && !stars.pay_for(12));
    let mut kept = stars.clone();
    kept.retain(|_| false);
    assert!(kept.is_empty() && kept.group(0) == NO_STAR && !kept.share(0, 4));
    // A book of five pages around the edge (0, 1): no star.
    let book = [[0, 1, 2], [1, 0, 3], [0, 1, 4], [0, 5, 1], [6, 0, 1]];
    assert!(Stars::new(book.len(), |k| Some(book[k]), 5).is_empty());
}

#[test]
fn degenerate_sectors() {
    let o = p(0, 0);
    assert_eq!(Sector::around(o, o, o), None);
    let ray = Sector::around(o, p(2, 0), p(5, 0)).unwrap();
    assert_eq!(ray.start, p(2, 0));
    assert_eq!(compare(o, ray.start, ray.end), Ordering::Equal);
    let half = Sector::around(o, p(2, 0), p(-5, 0)).unwrap();
    // The half turn from +x to -x goes through +y: it meets a sector
    // pointing up, not one pointing down.
    let down = Sector::around(o, p(0, -3), p(1, -3)).unwrap();
    let up = Sector::around(o, p(0, 3), p(1, 3)).unwrap();
    let pairs = sector_pairs(o, &[half, down, up], |_| true);
    assert_eq!(pairs, vec![(0, 2)]);
}

#[test]
fn paying_stars_are_new_stars_or_none() {
    // A fan of five around key 0 (12 pairs inside) and `lone` triangles
    // of their own: the star pays for 5 + `lone` triangles while 12 pairs
    // outnumber them.
    for lone in 0..10u32 {
        let mut tris: Vec<[u32; 3]> = (0..5).map(|k| [0, 1 + k, 2 + k]).collect();
        tris.extend((0..lone).map(|k| [100 + 3 * k, 101 + 3 * k, 102 + 3 * k]));
        let all = Stars::new(tris.len(), |k| Some(tris[k]), 5);
        let paying = Stars::paying(tris.len(), |k| Some(tris[k]), 5);
        assert_eq!(all.len(), 1);
        if 12 > tris.len() {
            assert_eq!(paying.members(0), all.members(0), "lone {lone}");
            assert!((0..tris.len()).all(|t| paying.stars_of(t) == all.stars_of(t)));
        } else {
            assert!(paying.is_empty(), "lone {lone}");
        }
    }
}
