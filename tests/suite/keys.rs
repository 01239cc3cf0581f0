//! The one key decoder (`terminal::input::Decoder`), for the local terminal and for `serve`:
//! crossterm's grammar, a paste bounded in bytes and time, ESC ESC as two things, replies to
//! terminal queries never keys. Hand-picked cases, then property tests: any bytes, split
//! anywhere, never panic; what a terminal sends for a key, a click or a paste decodes to it.

use crossterm::event::{
    Event, KeyCode, KeyEvent, KeyModifiers, MouseButton, MouseEvent, MouseEventKind,
};
use proptest::prelude::*;
use proptest::test_runner::RngSeed;
use std::time::{Duration, Instant};
use turntable::terminal::input::{
    Decoder, ESC_WAIT, Input, PASTE_END, PASTE_IDLE, PASTE_MAX, PASTE_START, PASTE_TIME,
};

/// The terminal's decoder, as `terminal::input::Reader` makes it.
fn local() -> Decoder {
    Decoder::new()
}

/// `serve`'s: a lone ESC ending a message is the Esc key at once.
fn ssh() -> Decoder {
    Decoder::with_esc_wait(Duration::ZERO)
}

/// Everything `bytes` decode to in one read, a held ESC let go.
fn decode(bytes: &[u8]) -> Vec<Input> {
    let mut d = local();
    let now = Instant::now();
    d.feed(bytes, false, now);
    d.expire(now + ESC_WAIT);
    std::iter::from_fn(|| d.next_input()).collect()
}

fn k(code: KeyCode, m: KeyModifiers) -> Input {
    Input::Event(key(code, m))
}

fn key(code: KeyCode, m: KeyModifiers) -> Event {
    Event::Key(KeyEvent::new(code, m))
}

fn click(kind: MouseEventKind, column: u16, row: u16, modifiers: KeyModifiers) -> Event {
    Event::Mouse(MouseEvent {
        kind,
        column,
        row,
        modifiers,
    })
}

#[test]
fn keys_as_crossterm_reads_them() {
    let none = KeyModifiers::NONE;
    let ctrl = KeyModifiers::CONTROL;
    let bytes = b"aQ\r\t\x7f\x03\x1b[A\x1b[1;2D\x1bOP\x1b[3~\x1b[Z\x1bx";
    let want = vec![
        key(KeyCode::Char('a'), none),
        key(KeyCode::Char('Q'), KeyModifiers::SHIFT),
        key(KeyCode::Enter, none),
        key(KeyCode::Tab, none),
        key(KeyCode::Backspace, none),
        key(KeyCode::Char('c'), ctrl),
        key(KeyCode::Up, none),
        key(KeyCode::Left, KeyModifiers::SHIFT),
        key(KeyCode::F(1), none),
        key(KeyCode::Delete, none),
        key(KeyCode::BackTab, KeyModifiers::SHIFT),
        key(KeyCode::Char('x'), KeyModifiers::ALT),
    ];
    assert_eq!(
        decode(bytes),
        want.iter().cloned().map(Input::Event).collect::<Vec<_>>()
    );
    // The same over SSH.
    let mut d = ssh();
    d.feed(bytes, false, Instant::now());
    assert_eq!(d.events(), want);
    assert_eq!(decode("ξ".as_bytes()), vec![k(KeyCode::Char('ξ'), none)]);
    assert_eq!(decode(b"\x1b"), vec![k(KeyCode::Esc, none)]);
    assert_eq!(decode(b"\x1b[12;40R"), vec![Input::Cursor(39, 11)]);
    assert_eq!(
        decode(b"\x1b[<0;5;3M\x1b[<0;5;3m"),
        vec![
            Input::Event(click(MouseEventKind::Down(MouseButton::Left), 4, 2, none)),
            Input::Event(click(MouseEventKind::Up(MouseButton::Left), 4, 2, none)),
        ]
    );
}

/// An Esc pressed as the terminal answers a cursor-position query: over ssh both arrive in one
/// read (`ESC ESC[30;21R`), or the reply's ESC ends one read and its tail begins the next.
/// Neither is `[30;21R` typed.
#[test]
fn a_reply_behind_an_esc_is_never_keys() {
    let esc = k(KeyCode::Esc, KeyModifiers::NONE);
    assert_eq!(
        decode(b"\x1b\x1b[30;21R"),
        vec![esc.clone(), Input::Cursor(20, 29)]
    );
    assert_eq!(
        decode(b"\x1b\x1b[A"),
        vec![esc.clone(), k(KeyCode::Up, KeyModifiers::NONE)]
    );
    let t0 = Instant::now();
    let mut d = local();
    d.feed(b"\x1b", false, t0);
    assert_eq!(d.next_input(), None, "a lone ESC waits for what may follow");
    assert_eq!(d.deadline(), Some(t0 + ESC_WAIT));
    d.feed(b"[30;21R", false, t0 + ESC_WAIT / 2);
    assert_eq!(d.next_input(), Some(Input::Cursor(20, 29)));
    assert_eq!(d.next_input(), None);
    // Alone, it is the Esc key once the wait is over.
    d.feed(b"\x1b", false, t0);
    d.expire(t0 + ESC_WAIT);
    assert_eq!(d.next_input(), Some(esc));
}

/// Over SSH a message holds a sequence whole: a lone ESC ending one is the key at once, and
/// serve, which waits for no cursor answer, takes replies for nothing.
#[test]
fn over_ssh_a_lone_esc_is_the_key_and_replies_are_nothing() {
    let none = KeyModifiers::NONE;
    let t0 = Instant::now();
    let mut d = ssh();
    d.feed(b"\x1b", false, t0);
    assert_eq!(d.events(), vec![key(KeyCode::Esc, none)]);
    assert_eq!(d.deadline(), None);
    d.feed(b"\x1b\x1b[30;21R", false, t0);
    assert_eq!(d.events(), vec![key(KeyCode::Esc, none)]);
    d.feed(b"\x1b[?1;2c\x1b[?7u", false, t0);
    assert_eq!(d.events(), vec![]);
    d.feed(b"\x1b\x1b[B", false, t0);
    assert_eq!(
        d.events(),
        vec![key(KeyCode::Esc, none), key(KeyCode::Down, none)]
    );
}

#[test]
fn a_paired_paste_is_one_event() {
    assert_eq!(
        decode(b"\x1b[200~sq\x1b[201~?"),
        vec![
            Input::Event(Event::Paste("sq".into())),
            k(KeyCode::Char('?'), KeyModifiers::NONE),
        ]
    );
}

/// No key is swallowed for good, by either decoder: an unpaired paste ends at Ctrl-C (which
/// then arrives), when its bytes stop, or in time.
#[test]
fn an_unpaired_paste_ends_at_ctrl_c_or_in_time() {
    for mut d in [local(), ssh()] {
        let t0 = Instant::now();
        d.feed(b"\x1b[200~abc", false, t0);
        assert!(d.pasting() && d.next_input().is_none());
        d.feed(b"q\x03q", false, t0);
        assert_eq!(
            d.events(),
            vec![
                Event::Paste("abcq".into()),
                key(KeyCode::Char('c'), KeyModifiers::CONTROL),
                key(KeyCode::Char('q'), KeyModifiers::NONE),
            ]
        );
        // Idle: ended PASTE_IDLE after its last byte, and keys are keys again.
        d.feed(b"\x1b[200~x", false, t0);
        d.expire(t0 + PASTE_IDLE / 2);
        assert!(d.pasting());
        assert_eq!(d.deadline(), Some(t0 + PASTE_IDLE));
        d.feed(b"q", false, t0 + PASTE_IDLE + PASTE_IDLE / 2);
        assert_eq!(
            d.events(),
            vec![
                Event::Paste("x".into()),
                key(KeyCode::Char('q'), KeyModifiers::NONE)
            ]
        );
        // Keys typed without a pause: ended PASTE_TIME after it began.
        d.feed(b"\x1b[200~", false, t0);
        let step = PASTE_IDLE / 2;
        let mut t = t0;
        while t < t0 + PASTE_TIME {
            t += step;
            d.feed(b"q", false, t);
        }
        assert!(!d.pasting(), "ended by PASTE_TIME");
    }
}

#[test]
fn a_long_paste_keeps_at_most_its_bound() {
    for mut d in [local(), ssh()] {
        let t0 = Instant::now();
        d.feed(PASTE_START, false, t0);
        let chunk = vec![b'a'; 64 * 1024];
        for _ in 0..(PASTE_MAX / chunk.len() + 4) {
            d.feed(&chunk, true, t0);
            assert!(d.next_input().is_none());
        }
        d.feed(PASTE_END, false, t0);
        match d.events().as_slice() {
            [Event::Paste(t)] => assert_eq!(t.len(), PASTE_MAX),
            other => panic!("{other:?}"),
        }
    }
}

#[test]
fn an_endless_sequence_is_dropped() {
    let mut bytes = b"\x1b[".to_vec();
    bytes.extend(std::iter::repeat_n(b'1', 200));
    bytes.push(b'q');
    assert_eq!(
        decode(&bytes).last(),
        Some(&k(KeyCode::Char('q'), KeyModifiers::NONE))
    );
}

fn config(cases: u32) -> ProptestConfig {
    ProptestConfig {
        cases,
        rng_seed: RngSeed::Fixed(45),
        failure_persistence: None,
        ..ProptestConfig::default()
    }
}

/// Bytes a terminal or a hostile client may send: any byte, and the pieces of sequences
/// (so that sequences begun, cut, nested and broken are common, not one in a million).
fn noise() -> impl Strategy<Value = Vec<u8>> {
    let piece = prop_oneof![
        any::<u8>().prop_map(|b| vec![b]),
        Just(b"\x1b".to_vec()),
        Just(b"\x1b[".to_vec()),
        Just(b"\x1b[<".to_vec()),
        Just(b"\x1b[M".to_vec()),
        Just(b"\x1bO".to_vec()),
        Just(PASTE_START.to_vec()),
        Just(PASTE_END.to_vec()),
        Just(b"\x03".to_vec()),
        Just(b";".to_vec()),
        Just(b"~".to_vec()),
        (0u32..70000).prop_map(|n| n.to_string().into_bytes()),
        prop::sample::select(b"MmRABCDHFPQSZu?c".to_vec()).prop_map(|b| vec![b]),
        Just("ξ".as_bytes()[..1].to_vec()),
    ];
    prop::collection::vec(piece, 0..80).prop_map(|v| v.concat())
}

/// The modifier parameter of a CSI key (1 + shift 1, alt 2, ctrl 4) and the modifiers read.
fn mods() -> impl Strategy<Value = (u8, KeyModifiers)> {
    (0u8..8).prop_map(|m| {
        let mut out = KeyModifiers::NONE;
        for (bit, flag) in [
            (1, KeyModifiers::SHIFT),
            (2, KeyModifiers::ALT),
            (4, KeyModifiers::CONTROL),
        ] {
            if m & bit != 0 {
                out |= flag;
            }
        }
        (m + 1, out)
    })
}

/// A key, a click or a paste, and the bytes a terminal sends for it (xterm's encoding, SGR
/// mouse reports, bracketed paste). Esc alone is left out: ESC and a letter is Alt and the
/// letter, for any reader (`a_reply_behind_an_esc_is_never_keys` covers Esc).
fn sent() -> impl Strategy<Value = (Event, Vec<u8>)> {
    let none = KeyModifiers::NONE;
    let text = prop_oneof![
        prop::char::range(' ', '~'),
        prop::sample::select(vec!['ξ', 'é', 'Ω', 'τ', '中', '€', '🙂']),
    ];
    let typed = text.clone().prop_map(|c| {
        let m = if c.is_uppercase() {
            KeyModifiers::SHIFT
        } else {
            KeyModifiers::NONE
        };
        (key(KeyCode::Char(c), m), c.to_string().into_bytes())
    });
    let alt =
        prop::sample::select(('a'..='z').chain('0'..='9').collect::<Vec<_>>()).prop_map(|c| {
            (
                key(KeyCode::Char(c), KeyModifiers::ALT),
                format!("\x1b{c}").into_bytes(),
            )
        });
    // Ctrl-I and Ctrl-M are Tab and Enter.
    let ctrl = prop::sample::select(
        ('a'..='z')
            .filter(|c| !"im".contains(*c))
            .collect::<Vec<_>>(),
    )
    .prop_map(|c| {
        (
            key(KeyCode::Char(c), KeyModifiers::CONTROL),
            vec![c as u8 - b'a' + 1],
        )
    });
    let named = prop::sample::select(vec![
        (KeyCode::Enter, none, &b"\r"[..]),
        (KeyCode::Tab, none, &b"\t"[..]),
        (KeyCode::Backspace, none, &b"\x7f"[..]),
        (KeyCode::BackTab, KeyModifiers::SHIFT, &b"\x1b[Z"[..]),
        (KeyCode::F(1), none, &b"\x1bOP"[..]),
        (KeyCode::F(4), none, &b"\x1bOS"[..]),
        (KeyCode::Up, none, &b"\x1bOA"[..]),
    ])
    .prop_map(|(c, m, b)| (key(c, m), b.to_vec()));
    let cursor = (
        prop::sample::select(vec![
            (KeyCode::Up, 'A'),
            (KeyCode::Down, 'B'),
            (KeyCode::Right, 'C'),
            (KeyCode::Left, 'D'),
            (KeyCode::End, 'F'),
            (KeyCode::Home, 'H'),
            (KeyCode::F(1), 'P'),
            (KeyCode::F(2), 'Q'),
            (KeyCode::F(4), 'S'),
        ]),
        mods(),
    )
        .prop_map(|((code, last), (p, m))| {
            let bytes = if p == 1 && !matches!(code, KeyCode::F(_)) {
                format!("\x1b[{last}")
            } else {
                format!("\x1b[1;{p}{last}")
            };
            (key(code, m), bytes.into_bytes())
        });
    let tilde = (
        prop::sample::select(vec![
            (KeyCode::Insert, 2),
            (KeyCode::Delete, 3),
            (KeyCode::PageUp, 5),
            (KeyCode::PageDown, 6),
            (KeyCode::F(5), 15),
            (KeyCode::F(6), 17),
            (KeyCode::F(8), 19),
            (KeyCode::F(10), 21),
            (KeyCode::F(11), 23),
            (KeyCode::F(12), 24),
        ]),
        mods(),
    )
        .prop_map(|((code, n), (p, m))| {
            let bytes = if p == 1 {
                format!("\x1b[{n}~")
            } else {
                format!("\x1b[{n};{p}~")
            };
            (key(code, m), bytes.into_bytes())
        });
    let mouse = (
        prop::sample::select(vec![
            (MouseEventKind::Down(MouseButton::Left), 0, 'M'),
            (MouseEventKind::Down(MouseButton::Middle), 1, 'M'),
            (MouseEventKind::Down(MouseButton::Right), 2, 'M'),
            (MouseEventKind::Up(MouseButton::Left), 0, 'm'),
            (MouseEventKind::Drag(MouseButton::Left), 32, 'M'),
            (MouseEventKind::Moved, 35, 'M'),
            (MouseEventKind::ScrollUp, 64, 'M'),
            (MouseEventKind::ScrollDown, 65, 'M'),
        ]),
        prop::sample::select(vec![
            (0, none),
            (4, KeyModifiers::SHIFT),
            (8, KeyModifiers::ALT),
            (16, KeyModifiers::CONTROL),
        ]),
        0u16..1000,
        0u16..1000,
    )
        .prop_map(|((kind, cb, end), (bits, m), x, y)| {
            let bytes = format!("\x1b[<{};{};{}{end}", cb + bits, x + 1, y + 1);
            (click(kind, x, y, m), bytes.into_bytes())
        });
    let paste = prop::collection::vec(prop_oneof![text, Just('\r'), Just('\n'), Just('\t')], 0..40)
        .prop_map(|cs| {
            let t: String = cs.into_iter().collect();
            let bytes = [PASTE_START, t.as_bytes(), PASTE_END].concat();
            (Event::Paste(t), bytes)
        });
    prop_oneof![
        4 => typed,
        1 => alt,
        1 => ctrl,
        1 => named,
        2 => cursor,
        2 => tilde,
        2 => mouse,
        1 => paste,
    ]
}

proptest! {
    #![proptest_config(config(256))]

    /// Any bytes, cut anywhere, at any pace, by either decoder: no panic, and a paste holds at
    /// most its bound.
    #[test]
    fn any_bytes_cut_anywhere_never_panic(
        bytes in noise(),
        cuts in prop::collection::vec((0usize..64, any::<bool>(), 0u64..800), 0..12),
    ) {
        for mut d in [local(), ssh()] {
            let mut t = Instant::now();
            let mut rest = &bytes[..];
            for &(n, more, ms) in &cuts {
                let (now, later) = rest.split_at(n.min(rest.len()));
                d.feed(now, more, t);
                rest = later;
                t += Duration::from_millis(ms);
                d.expire(t);
                let _ = d.deadline();
            }
            d.feed(rest, false, t);
            d.expire(t + PASTE_TIME);
            prop_assert!(!d.pasting());
            while let Some(x) = d.next_input() {
                if let Input::Event(Event::Paste(p)) = x {
                    prop_assert!(p.len() <= PASTE_MAX);
                }
            }
        }
    }

    /// What a terminal sends for keys, clicks and pastes decodes to them: in one read, and cut
    /// into reads anywhere (the terminal's decoder; an SSH message holds a sequence whole).
    #[test]
    fn what_a_terminal_sends_decodes_to_what_was_done(
        sent in prop::collection::vec(sent(), 0..16),
        esc_last in any::<bool>(),
        cuts in prop::collection::vec(1usize..12, 0..20),
    ) {
        let (mut want, bytes): (Vec<Event>, Vec<Vec<u8>>) = sent.into_iter().unzip();
        let mut bytes = bytes.concat();
        if esc_last {
            want.push(key(KeyCode::Esc, KeyModifiers::NONE));
            bytes.push(0x1b);
        }
        let t0 = Instant::now();
        let mut whole = ssh();
        whole.feed(&bytes, false, t0);
        prop_assert_eq!(whole.events(), want.clone());
        let mut cut = local();
        let mut rest = &bytes[..];
        for n in cuts {
            let (now, later) = rest.split_at(n.min(rest.len()));
            cut.feed(now, false, t0);
            rest = later;
        }
        cut.feed(rest, false, t0);
        cut.expire(t0 + ESC_WAIT);
        prop_assert_eq!(cut.events(), want);
    }
}
