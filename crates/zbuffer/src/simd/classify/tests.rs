//! The AVX2 classification against the portable one.

use hider_geom::isa::Avx2;
use hider_geom::{FixedPt, Viewport};
use proptest::prelude::*;

use crate::depth_scene::SmallSetup;
use crate::depth_scene::classify::{LANES, Lanes};

/// A batch's corners: small triangles around random points (boxes of a
/// few centres, on or off the viewport) mixed with large ones and ones
/// across the image's corner, in subpixel units.
fn batch() -> impl Strategy<Value = [[(i32, i32); 3]; LANES]> {
    let corner = |r: i32| (-r..r, -r..r);
    let small = (
        (-600i32..5000, -600i32..5000),
        proptest::array::uniform3(corner(600)),
    )
        .prop_map(|((x, y), d)| d.map(|(dx, dy)| (x + dx, y + dy)));
    let large = proptest::array::uniform3((-(1 << 22)..1 << 22, -(1 << 22)..1 << 22));
    // Across the image's top-left corner, far beyond it: a box of a
    // few centres once clamped, with corners too far for `i32`.
    let across = (
        (0i32..700, 0i32..700),
        (-(1i32 << 22)..-(1 << 14), 0i32..700),
        (0i32..700, -(1i32 << 22)..-(1 << 14)),
    )
        .prop_map(|(a, b, c)| [a, b, c]);
    proptest::array::uniform8(prop_oneof![4 => small, 1 => large, 1 => across])
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(2000))]
    /// The AVX2 classification is the portable one, field for field.
    #[test]
    fn avx2_classifies_as_the_portable_code(
        tris in batch(),
        size in (1u32..40, 1u32..40),
        cull: bool,
    ) {
        let Some(avx2) = Avx2::detect() else { return Ok(()) };
        let x = std::array::from_fn(|k| std::array::from_fn(|i| tris[i][k].0));
        let y = std::array::from_fn(|k| std::array::from_fn(|i| tris[i][k].1));
        let portable = Lanes::classify(&x, &y, size, cull);
        let wide = super::classify(avx2, &x, &y, size, cull);
        prop_assert_eq!(&wide, &portable);
        // The set-ups of the lanes kept as triangles are the scalar
        // definition's.
        let want = wide.keep & !wide.few;
        let setups = super::setups(avx2, &x, &y, size, (wide.swap, want));
        let viewport = Viewport::new(size.0, size.1);
        for i in 0..LANES {
            let got = setups.get(i);
            let expected = if want >> i & 1 == 0 {
                SmallSetup::NONE
            } else {
                let (b, c) = if wide.swap >> i & 1 != 0 { (2, 1) } else { (1, 2) };
                let v = [0, b, c].map(|k| FixedPt::new(x[k][i], y[k][i]));
                SmallSetup::new(&v, viewport)
            };
            prop_assert_eq!(got, expected, "lane {}", i);
        }
    }
}
