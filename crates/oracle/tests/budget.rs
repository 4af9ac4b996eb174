//! The oracle's memory budget: an image whose working arrays would not fit
//! is refused before anything is allocated (16384 x 16384 pixels once took
//! 24 GB and was killed).

use hider_oracle::{OracleOptions, RayCastOracle};
use hider_scene::{Error, Frame, Hider, procedural};
use hider_testkit::screen;

#[test]
fn a_16384_pixel_image_is_refused_before_allocating() {
    let s = screen(&procedural::cube(), 16384, 16384);
    let need = RayCastOracle::bytes_needed(16384, 16384);
    assert!(need > 20 << 30, "{need}");
    match RayCastOracle::default().try_evaluate(&s) {
        Err(Error::Budget { what, value, limit }) => {
            assert_eq!(what, "oracle working bytes");
            assert_eq!(value, need);
            assert_eq!(limit, hider_oracle::DEFAULT_MAX_BYTES);
        }
        other => panic!("expected the byte budget's refusal, got {other:?}"),
    }
}

#[test]
fn render_refuses_over_budget_and_keeps_the_frame() {
    let s = screen(&procedural::cube(), 64, 64);
    let need = RayCastOracle::bytes_needed(64, 64);
    let mut frame = Frame::new(64, 64).unwrap();
    frame.ids[5] = 7;
    let mut tight = RayCastOracle::new(OracleOptions::default().with_max_bytes(need - 1));
    let e = tight.render(&s, &mut frame).unwrap_err();
    assert!(
        e.to_string().contains("oracle working bytes"),
        "one line naming the budget: {e}"
    );
    assert_eq!(frame.ids[5], 7, "nothing drawn");
    // Exactly the need fits, and the stats report what was held.
    let mut fits = RayCastOracle::new(OracleOptions::default().with_max_bytes(need));
    let stats = fits.render(&s, &mut frame).unwrap();
    assert!(stats.hits > 0);
    assert!(stats.peak_bytes <= need, "{} > {need}", stats.peak_bytes);
}

#[test]
fn check_size_refuses_the_16384_image_before_a_frame_exists() {
    // The same refusal as `try_evaluate`, from the size alone: a caller
    // asks before allocating its 16384 x 16384 frame.
    let oracle = RayCastOracle::default();
    let e = oracle.check_size(16384, 16384).unwrap_err();
    assert!(
        matches!(e, Error::Budget { value, .. } if value == RayCastOracle::bytes_needed(16384, 16384)),
        "{e}"
    );
    oracle.check_size(1024, 1024).unwrap();
    let need = RayCastOracle::bytes_needed(64, 64);
    let tight = RayCastOracle::new(OracleOptions::default().with_max_bytes(need - 1));
    assert!(tight.check_size(64, 64).is_err());
    assert!(tight.check_size(63, 64).is_ok());
}
