//! One SSH connection: who it is (a key or a passphrase, else nothing), and what it may ask
//! for: one session channel with a PTY and a shell, which gets an explorer. A command
//! (exec), a subsystem (SFTP), X11, agent and port forwarding are refused; the default
//! handlers refuse the other channel kinds.

use super::explorer::{self, Client, Outbox};
use super::out::{Flushed, Guarded, UNSENT_MAX, write_out};
use super::{In, Shared, auth};
use russh::keys::PublicKey;
use russh::server::{Auth, Handler, Msg, Session};
use russh::{Channel, ChannelId, ChannelWriteHalf, MethodKind, MethodSet, Pty};
use std::sync::Arc;
use std::sync::atomic::{AtomicBool, Ordering};
use std::time::Duration;

/// The server's SSH configuration: the host key, public key and password methods only, a
/// second's wait on a refusal, keepalives that find a half-open connection in a minute.
pub fn config(options: &super::Options) -> russh::server::Config {
    let mut methods = MethodSet::empty();
    methods.push(MethodKind::PublicKey);
    methods.push(MethodKind::Password);
    russh::server::Config {
        keys: vec![options.host_key.clone()],
        methods,
        auth_rejection_time: Duration::from_secs(1),
        auth_rejection_time_initial: Some(Duration::ZERO),
        max_auth_attempts: 6,
        inactivity_timeout: None,
        keepalive_interval: Some(Duration::from_secs(15)),
        keepalive_max: 4,
        nodelay: true,
        ..Default::default()
    }
}

/// Serves one TCP connection until it ends: closed if it is not in within the handshake's
/// time.
pub async fn serve(tcp: tokio::net::TcpStream, shared: Arc<Shared>) {
    let _ = tcp.set_nodelay(true);
    // The kernel holds at most this much unsent: on a slow link the socket, not a deep buffer
    // behind it, says when a frame has left (see `Flushed`).
    let _ = socket2::SockRef::from(&tcp).set_tcp_notsent_lowat(UNSENT_MAX);
    let flushed = Arc::new(Flushed::default());
    let authed = Arc::new(AtomicBool::new(false));
    let handler = Conn {
        shared: Arc::clone(&shared),
        authed: Arc::clone(&authed),
        presenter: false,
        channel: None,
        client: Client::default(),
        session: None,
        ended: tokio::sync::watch::channel(()).0,
        flushed: Arc::clone(&flushed),
    };
    let stream = Guarded::new(tcp, shared.limits.stall, flushed);
    let limit = shared.limits.handshake;
    let Ok(Ok(running)) = tokio::time::timeout(
        limit,
        russh::server::run_stream(Arc::clone(&shared.config), stream, handler),
    )
    .await
    else {
        return;
    };
    let handle = running.handle();
    tokio::pin!(running);
    tokio::select! {
        _ = &mut running => return,
        () = tokio::time::sleep(limit) => {}
    }
    if !authed.load(Ordering::Relaxed) {
        let _ = handle
            .disconnect(
                russh::Disconnect::ByApplication,
                "not authenticated in time".into(),
                String::new(),
            )
            .await;
        return;
    }
    let _ = running.await;
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
    authed: Arc<AtomicBool>,
    presenter: bool,
    /// The session channel, until its shell starts.
    channel: Option<(ChannelId, ChannelWriteHalf<Msg>)>,
    client: Client,
    /// The explorer's inbox, once started.
    session: Option<(ChannelId, std::sync::mpsc::Sender<In>)>,
    /// Dropped with the connection: its writer stops then (see [`write_out`]).
    ended: tokio::sync::watch::Sender<()>,
    /// The bytes written to the socket so far.
    flushed: Arc<Flushed>,
}

const REFUSED: &str = "turntable serves the explorer only: `ssh -t` to this address opens it\r\n";

impl Conn {
    fn who(&mut self, key: Option<&PublicKey>, password: Option<&str>) -> Auth {
        let o = &self.shared.options;
        let presenter = key.is_some_and(|k| auth::known(&o.presenter_keys, k))
            || password.is_some_and(|p| {
                o.presenter_passphrase
                    .as_deref()
                    .is_some_and(|e| auth::same(p, e))
            });
        let guest = key.is_some_and(|k| auth::known(&o.keys, k))
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
        if let Some((_, tx)) = &self.session {
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

    fn refuse(&mut self, channel: ChannelId, session: &mut Session) -> Result<(), russh::Error> {
        session.channel_failure(channel)?;
        session.extended_data(channel, 1, REFUSED.as_bytes().to_vec())?;
        session.exit_status_request(channel, 1)?;
        session.close(channel)?;
        self.channel = None;
        Ok(())
    }
}

impl Drop for Conn {
    fn drop(&mut self) {
        if let Some((_, tx)) = &self.session {
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
            if auth::known(&o.keys, key) || auth::known(&o.presenter_keys, key) {
                Auth::Accept
            } else {
                Auth::reject()
            },
        )
    }

    async fn auth_publickey(&mut self, _user: &str, key: &PublicKey) -> Result<Auth, Self::Error> {
        Ok(self.who(Some(key), None))
    }

    async fn auth_password(&mut self, _user: &str, password: &str) -> Result<Auth, Self::Error> {
        Ok(self.who(None, Some(password)))
    }

    async fn auth_succeeded(&mut self, _session: &mut Session) -> Result<(), Self::Error> {
        self.authed.store(true, Ordering::Relaxed);
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
            _ => return session.channel_failure(channel),
        }
        session.channel_success(channel)
    }

    async fn shell_request(
        &mut self,
        channel: ChannelId,
        session: &mut Session,
    ) -> Result<(), Self::Error> {
        let Some((id, write)) = self.channel.take().filter(|(id, _)| *id == channel) else {
            return session.channel_failure(channel);
        };
        let (tx, rx) = std::sync::mpsc::channel();
        let Some(number) = self.shared.enter(tx.clone(), self.presenter) else {
            session.channel_failure(channel)?;
            let full = format!(
                "turntable: the class is full ({} sessions); try again later\r\n",
                self.shared.limits.sessions
            );
            session.data(channel, full.into_bytes())?;
            session.exit_status_request(channel, 1)?;
            return session.close(channel);
        };
        session.channel_success(channel)?;
        if self.client.width == 0 || self.client.height == 0 {
            (self.client.width, self.client.height) = (80, 24);
        }
        let (out_tx, out_rx) = tokio::sync::mpsc::channel(2);
        tokio::spawn(write_out(
            write,
            out_rx,
            tx.clone(),
            self.ended.subscribe(),
            Arc::clone(&self.flushed),
        ));
        let shared = Arc::clone(&self.shared);
        let client = self.client.clone();
        let started = std::thread::Builder::new()
            .name("turntable-session".into())
            .spawn(move || explorer::run(shared, number, client, rx, Outbox(out_tx)));
        if started.is_err() {
            self.shared.leave(number);
            return session.close(channel);
        }
        self.session = Some((id, tx));
        Ok(())
    }

    async fn exec_request(
        &mut self,
        channel: ChannelId,
        _data: &[u8],
        session: &mut Session,
    ) -> Result<(), Self::Error> {
        self.refuse(channel, session)
    }

    async fn subsystem_request(
        &mut self,
        channel: ChannelId,
        _name: &str,
        session: &mut Session,
    ) -> Result<(), Self::Error> {
        self.refuse(channel, session)
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
        self.forward(In::Resize(w, h));
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
