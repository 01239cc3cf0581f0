//! One SSH connection: who it is (a key or a passphrase, else nothing), and what it may ask
//! for: one session channel with a PTY and a shell, which gets an explorer. A command
//! (exec), a subsystem (SFTP), X11, agent and port forwarding are refused; the default
//! handlers refuse the other channel kinds.

use super::door::Pass;
use super::explorer::{self, Client, Outbox, PLAIN_USER};
use super::keyfile::{self, Authorized};
use super::out::{Flushed, Guarded, UNSENT_MAX, write_out};
use super::screen::Window;
use super::{In, Shared, auth};
use russh::keys::PublicKey;
use russh::server::{Auth, Handler, Msg, Session};
use russh::{Channel, ChannelId, ChannelWriteHalf, MethodKind, MethodSet, Pty};
use std::sync::Arc;
use std::sync::atomic::Ordering;
use std::time::{Duration, Instant};

/// The server's SSH configuration: the host key, public key and password methods only, the
/// limits' wait on a refusal, keepalives that find a half-open connection in a minute.
pub fn config(options: &super::Options) -> russh::server::Config {
    let mut methods = MethodSet::empty();
    methods.push(MethodKind::PublicKey);
    methods.push(MethodKind::Password);
    russh::server::Config {
        keys: vec![options.host_key.clone()],
        methods,
        auth_rejection_time: options.limits.refusal,
        auth_rejection_time_initial: Some(Duration::ZERO),
        max_auth_attempts: 6,
        inactivity_timeout: None,
        keepalive_interval: Some(Duration::from_secs(15)),
        keepalive_max: 4,
        nodelay: true,
        ..Default::default()
    }
}

/// Where a connection is: each stage but the explorer's has its time (see [`serve`]).
#[derive(Clone, Copy, Debug, PartialEq)]
enum Stage {
    /// Not in yet.
    Knocking,
    /// In, and no explorer yet (since then).
    In(Instant),
    /// Its explorer runs.
    Seated,
    /// Its explorer has ended (since then).
    Done(Instant),
}

/// Serves one TCP connection until it ends: closed if it is not in within the handshake's
/// time, if it has no explorer within the shell's grace after that or after its explorer
/// ended, or when the door needs its place.
pub async fn serve(tcp: tokio::net::TcpStream, shared: Arc<Shared>, pass: Pass) {
    let _ = tcp.set_nodelay(true);
    // The kernel holds at most this much unsent: on a slow link the socket, not a deep buffer
    // behind it, says when a frame has left (see `Flushed`).
    let _ = socket2::SockRef::from(&tcp).set_tcp_notsent_lowat(UNSENT_MAX);
    let flushed = Arc::new(Flushed::default());
    let Ok(peer) = tcp.peer_addr() else {
        return;
    };
    let (stage, mut staged) = tokio::sync::watch::channel(Stage::Knocking);
    let go = Arc::clone(&pass.go);
    let handler = Conn {
        shared: Arc::clone(&shared),
        pass,
        peer: peer.ip(),
        stage: Arc::new(stage),
        presenter: false,
        channel: None,
        client: Client::default(),
        session: None,
        ended: tokio::sync::watch::channel(()).0,
        flushed: Arc::clone(&flushed),
        password_tries: 0,
    };
    let stream = Guarded::new(tcp, shared.limits.stall, flushed);
    let l = shared.limits;
    let knocked = Instant::now();
    let run = russh::server::run_stream(Arc::clone(&shared.config), stream, handler);
    let running = tokio::select! {
        r = tokio::time::timeout(l.handshake, run) => match r {
            Ok(Ok(running)) => running,
            _ => return,
        },
        () = go.notified() => return,
    };
    let handle = running.handle();
    tokio::pin!(running);
    loop {
        let now = *staged.borrow_and_update();
        let (until, why) = match now {
            Stage::Knocking => (knocked + l.handshake, "not authenticated in time"),
            Stage::In(since) => (since + l.shell_grace, "no shell asked for in time"),
            Stage::Done(since) => (since + l.shell_grace, "the explorer has ended"),
            Stage::Seated => (knocked + Duration::from_secs(1 << 30), ""),
        };
        let why = tokio::select! {
            _ = &mut running => return,
            r = staged.changed() => match r {
                Ok(()) => continue,
                Err(_) => {
                    let _ = running.await;
                    return;
                }
            },
            () = go.notified() => match now {
                Stage::Knocking => "too many connections waiting to log in: try again",
                _ => "too many connections logged in without an explorer: closed",
            },
            () = tokio::time::sleep_until(until.into()) => why,
        };
        let _ = handle
            .disconnect(russh::Disconnect::ByApplication, why.into(), String::new())
            .await;
        return;
    }
}

/// Input bytes on their way to a session, counted in [`Shared`]'s queue until dropped: taken,
/// or left unread by a session that ended (which, uncounted, held everyone's input up for
/// good once a flood's remains passed the bound).
pub struct Queued {
    bytes: Vec<u8>,
    shared: Arc<Shared>,
}

impl Queued {
    fn new(bytes: Vec<u8>, shared: &Arc<Shared>) -> Queued {
        shared.queued.fetch_add(bytes.len(), Ordering::Relaxed);
        Queued {
            bytes,
            shared: Arc::clone(shared),
        }
    }
}

impl std::ops::Deref for Queued {
    type Target = [u8];
    fn deref(&self) -> &[u8] {
        &self.bytes
    }
}

impl Drop for Queued {
    fn drop(&mut self) {
        self.shared
            .queued
            .fetch_sub(self.bytes.len(), Ordering::Relaxed);
    }
}

/// Input queued beyond this waits (the connection stops reading): a flood of keys costs
/// memory up to this bound only.
const QUEUED_MAX: usize = 1 << 20;

/// One connection's state.
struct Conn {
    shared: Arc<Shared>,
    /// Its place at the door.
    pass: Pass,
    /// The client's address, as a key's `from=` sees it.
    peer: std::net::IpAddr,
    stage: Arc<tokio::sync::watch::Sender<Stage>>,
    presenter: bool,
    /// Passphrases refused so far.
    password_tries: u32,
    /// The session channel, until its shell starts.
    channel: Option<(ChannelId, ChannelWriteHalf<Msg>)>,
    client: Client,
    /// The explorer's inbox and the client's window size, once started.
    session: Option<(std::sync::mpsc::Sender<In>, Arc<Window>)>,
    /// Dropped with the connection: its writer stops then (see [`write_out`]).
    ended: tokio::sync::watch::Sender<()>,
    /// The bytes written to the socket so far.
    flushed: Arc<Flushed>,
}

const REFUSED: &str = "turntable serves the explorer only: `ssh -t` to this address opens it\r\n";

/// Passphrases a connection may try (OpenSSH's client asks three times).
const PASSWORD_TRIES: u32 = 3;

impl Conn {
    /// Whether `key` is among `keys`, from this client's address, now.
    fn admits(&self, keys: &[Authorized], key: &PublicKey) -> bool {
        let now = keyfile::now();
        keys.iter().any(|k| k.admits(key, self.peer, now))
    }

    fn who(&mut self, key: Option<&PublicKey>, password: Option<&str>) -> Auth {
        let o = &self.shared.options;
        let presenter = key.is_some_and(|k| self.admits(&o.presenter_keys, k))
            || password.is_some_and(|p| {
                o.presenter_passphrase
                    .as_deref()
                    .is_some_and(|e| auth::same(p, e))
            });
        let guest = key.is_some_and(|k| self.admits(&o.keys, k))
            || password.is_some_and(|p| o.passphrase.as_deref().is_some_and(|e| auth::same(p, e)));
        if presenter || guest {
            self.presenter = presenter;
            Auth::Accept
        } else {
            Auth::reject()
        }
    }

    /// The message reaches the explorer.
    fn forward(&self, msg: In) {
        if let Some((tx, _)) = &self.session {
            let _ = tx.send(msg);
        }
    }

    /// The input reaches the explorer; a flood waits here, so the connection stops reading.
    async fn input(&self, data: &[u8]) {
        while self.shared.queued.load(Ordering::Relaxed) > QUEUED_MAX {
            tokio::time::sleep(Duration::from_millis(5)).await;
        }
        self.forward(In::Data(Queued::new(data.to_vec(), &self.shared)));
    }

    /// Refuses the channel's request, saying why where OpenSSH shows it: the request is taken
    /// and the channel ends at once with the message on its error stream and exit status 1 (a
    /// refused shell or exec makes OpenSSH exit before it prints what came after).
    fn refuse(
        &mut self,
        channel: ChannelId,
        why: &str,
        session: &mut Session,
    ) -> Result<(), russh::Error> {
        session.channel_success(channel)?;
        session.extended_data(channel, 1, why.as_bytes().to_vec())?;
        session.exit_status_request(channel, 1)?;
        session.eof(channel)?;
        session.close(channel)?;
        self.channel = None;
        Ok(())
    }
}

impl Drop for Conn {
    fn drop(&mut self) {
        if let Some((tx, _)) = &self.session {
            let _ = tx.send(In::Close(String::new()));
        }
    }
}

impl Handler for Conn {
    type Error = russh::Error;

    async fn auth_publickey_offered(
        &mut self,
        _user: &str,
        key: &PublicKey,
    ) -> Result<Auth, Self::Error> {
        let o = &self.shared.options;
        Ok(
            if self.admits(&o.keys, key) || self.admits(&o.presenter_keys, key) {
                Auth::Accept
            } else {
                Auth::reject()
            },
        )
    }

    async fn auth_publickey(&mut self, user: &str, key: &PublicKey) -> Result<Auth, Self::Error> {
        self.client.plain = user == PLAIN_USER;
        Ok(self.who(Some(key), None))
    }

    async fn auth_password(&mut self, user: &str, password: &str) -> Result<Auth, Self::Error> {
        self.client.plain = user == PLAIN_USER;
        // Past its tries nothing is compared (russh would still ask this handler).
        if self.password_tries >= PASSWORD_TRIES {
            return Ok(Auth::reject());
        }
        let auth = self.who(None, Some(password));
        if matches!(auth, Auth::Accept) {
            return Ok(auth);
        }
        // A typo is answered with another try, up to PASSWORD_TRIES (russh, told nothing,
        // takes the password method away after the first).
        self.password_tries += 1;
        if self.password_tries >= PASSWORD_TRIES {
            return Ok(auth);
        }
        let mut methods = MethodSet::empty();
        methods.push(MethodKind::PublicKey);
        methods.push(MethodKind::Password);
        Ok(Auth::Reject {
            proceed_with_methods: Some(methods),
            partial_success: false,
        })
    }

    async fn auth_succeeded(&mut self, _session: &mut Session) -> Result<(), Self::Error> {
        self.pass.logged_in();
        self.stage.send_replace(Stage::In(Instant::now()));
        Ok(())
    }

    async fn channel_open_session(
        &mut self,
        channel: Channel<Msg>,
        reply: russh::server::ChannelOpenHandle,
        _session: &mut Session,
    ) -> Result<(), Self::Error> {
        // One explorer a connection; a second channel is refused (the handle dropped).
        if self.channel.is_some() || self.session.is_some() {
            return Ok(());
        }
        // Input arrives through `data`: the channel's own reader is dropped, so it never
        // fills and holds the connection up.
        let (_read, write) = channel.split();
        self.channel = Some((write.id(), write));
        reply.accept().await;
        Ok(())
    }

    async fn pty_request(
        &mut self,
        channel: ChannelId,
        term: &str,
        col_width: u32,
        row_height: u32,
        _pix_width: u32,
        _pix_height: u32,
        _modes: &[(Pty, u32)],
        session: &mut Session,
    ) -> Result<(), Self::Error> {
        self.client.term = term.chars().take(64).collect();
        self.client.width = u16::try_from(col_width).unwrap_or(u16::MAX);
        self.client.height = u16::try_from(row_height).unwrap_or(u16::MAX);
        session.channel_success(channel)
    }

    async fn env_request(
        &mut self,
        channel: ChannelId,
        name: &str,
        value: &str,
        session: &mut Session,
    ) -> Result<(), Self::Error> {
        let value = Some(value.chars().take(64).collect());
        match name {
            "LANG" | "LC_ALL" | "LC_CTYPE" => self.client.lang = value,
            "COLORTERM" => self.client.colorterm = value,
            // `ssh -o SetEnv=TURNTABLE_PLAIN=1` (or SendEnv): plain mode whatever the user
            // name; 0 or empty turns it off.
            "TURNTABLE_PLAIN" => self.client.plain = !matches!(value.as_deref(), Some("" | "0")),
            _ => return session.channel_failure(channel),
        }
        session.channel_success(channel)
    }

    async fn shell_request(
        &mut self,
        channel: ChannelId,
        session: &mut Session,
    ) -> Result<(), Self::Error> {
        let Some((_, write)) = self.channel.take().filter(|(id, _)| *id == channel) else {
            return session.channel_failure(channel);
        };
        let (tx, rx) = std::sync::mpsc::channel();
        let Some(number) = self.shared.enter(tx.clone(), self.presenter) else {
            let n = self.shared.limits.sessions;
            let full = format!(
                "turntable: the class is full ({n} session{}); try again later\r\n",
                if n == 1 { "" } else { "s" }
            );
            return self.refuse(channel, &full, session);
        };
        session.channel_success(channel)?;
        self.pass.seated();
        self.stage.send_replace(Stage::Seated);
        if self.client.width == 0 || self.client.height == 0 {
            (self.client.width, self.client.height) = (80, 24);
        }
        let (out_tx, out_rx) = tokio::sync::mpsc::channel(2);
        let writer = write_out(
            write,
            out_rx,
            tx.clone(),
            self.ended.subscribe(),
            Arc::clone(&self.flushed),
        );
        let stage = Arc::clone(&self.stage);
        tokio::spawn(async move {
            writer.await;
            stage.send_replace(Stage::Done(Instant::now()));
        });
        let shared = Arc::clone(&self.shared);
        let client = self.client.clone();
        let size = Arc::new(Window::new(client.width, client.height));
        let for_session = Arc::clone(&size);
        let started = std::thread::Builder::new()
            .name("turntable-session".into())
            .spawn(move || explorer::run(shared, number, client, for_session, rx, Outbox(out_tx)));
        if started.is_err() {
            self.shared.leave(number);
            return session.close(channel);
        }
        self.session = Some((tx, size));
        Ok(())
    }

    async fn exec_request(
        &mut self,
        channel: ChannelId,
        _data: &[u8],
        session: &mut Session,
    ) -> Result<(), Self::Error> {
        self.refuse(channel, REFUSED, session)
    }

    /// Refused outright: a subsystem's client (sftp) would read the message as its protocol.
    async fn subsystem_request(
        &mut self,
        channel: ChannelId,
        _name: &str,
        session: &mut Session,
    ) -> Result<(), Self::Error> {
        session.channel_failure(channel)?;
        session.close(channel)?;
        self.channel = None;
        Ok(())
    }

    async fn x11_request(
        &mut self,
        channel: ChannelId,
        _single_connection: bool,
        _x11_auth_protocol: &str,
        _x11_auth_cookie: &str,
        _x11_screen_number: u32,
        session: &mut Session,
    ) -> Result<(), Self::Error> {
        session.channel_failure(channel)
    }

    async fn window_change_request(
        &mut self,
        _channel: ChannelId,
        col_width: u32,
        row_height: u32,
        _pix_width: u32,
        _pix_height: u32,
        _session: &mut Session,
    ) -> Result<(), Self::Error> {
        let w = u16::try_from(col_width).unwrap_or(u16::MAX);
        let h = u16::try_from(row_height).unwrap_or(u16::MAX);
        self.client.width = w;
        self.client.height = h;
        if let Some((_, size)) = &self.session
            && size.set(w, h)
        {
            self.forward(In::Resize);
        }
        Ok(())
    }

    async fn data(
        &mut self,
        _channel: ChannelId,
        data: &[u8],
        _session: &mut Session,
    ) -> Result<(), Self::Error> {
        self.input(data).await;
        Ok(())
    }

    async fn channel_eof(
        &mut self,
        _channel: ChannelId,
        _session: &mut Session,
    ) -> Result<(), Self::Error> {
        self.forward(In::Close(String::new()));
        Ok(())
    }

    async fn channel_close(
        &mut self,
        _channel: ChannelId,
        _session: &mut Session,
    ) -> Result<(), Self::Error> {
        self.forward(In::Close(String::new()));
        Ok(())
    }
}
