//! An SSH client of the explorer in this process (russh's client): what the tests and the
//! bench drive the server with over the loopback, as a student's `ssh` would.

use russh::ChannelMsg;
use russh::client::{Handle, Msg};
use russh::keys::{PrivateKey, PrivateKeyWithHashAlg};
use std::net::SocketAddr;
use std::pin::Pin;
use std::sync::Arc;
use std::sync::atomic::{AtomicBool, Ordering};
use std::task::{Context, Poll};
use std::time::Duration;
use tokio::io::{AsyncRead, AsyncWrite, ReadBuf};
use tokio::net::TcpStream;
use tokio::time::Instant;

/// Trusts the server's key: the tests make it, and check its fingerprint elsewhere.
pub struct Trust;

impl russh::client::Handler for Trust {
    type Error = russh::Error;

    async fn check_server_key(
        &mut self,
        _key: &russh::keys::PublicKeyOrCertificate,
    ) -> Result<bool, Self::Error> {
        Ok(true)
    }
}

/// How a client gets in.
pub enum Login<'a> {
    Key(&'a PrivateKey),
    Password(&'a str),
}

/// A client's SSH configuration: russh's, but with Nagle's algorithm off, as OpenSSH's `ssh`
/// sets for an interactive session (with it on, each small write after the first waited for
/// the server's delayed ACK: 40 ms a login step and a key).
pub fn config() -> russh::client::Config {
    russh::client::Config {
        nodelay: true,
        ..Default::default()
    }
}

/// Connects to `addr` and logs in as `user`; `Ok(None)` when refused.
pub async fn login(
    addr: SocketAddr,
    user: &str,
    how: Login<'_>,
) -> Result<Option<Handle<Trust>>, russh::Error> {
    let config = Arc::new(config());
    let mut handle = russh::client::connect(config, addr, Trust).await?;
    let ok = match how {
        Login::Key(key) => {
            let key = PrivateKeyWithHashAlg::new(Arc::new(key.clone()), None);
            handle.authenticate_publickey(user, key).await?
        }
        Login::Password(p) => handle.authenticate_password(user, p).await?,
    };
    Ok(ok.success().then_some(handle))
}

/// Logs in by `key` on a connection that stops reading its screen once the flag it returns
/// is set: a client that never reads, with a channel window of `window` bytes.
pub async fn frozen_login(
    addr: SocketAddr,
    user: &str,
    key: &PrivateKey,
    window: u32,
) -> Result<Option<(Handle<Trust>, Arc<AtomicBool>)>, russh::Error> {
    let link = Link::new(TcpStream::connect(addr).await?, None);
    let frozen = Arc::clone(&link.frozen);
    let config = russh::client::Config {
        window_size: window,
        ..config()
    };
    let handle = login_over(link, config, user, key).await?;
    Ok(handle.map(|h| (h, frozen)))
}

/// Logs in by `key` over a link that carries at most `rate` bytes a second to the client, with
/// a small socket buffer: a student on a slow link.
pub async fn slow_login(
    addr: SocketAddr,
    user: &str,
    key: &PrivateKey,
    rate: usize,
) -> Result<Option<Handle<Trust>>, russh::Error> {
    let socket = tokio::net::TcpSocket::new_v4()?;
    socket.set_recv_buffer_size(4096)?;
    let link = Link::new(socket.connect(addr).await?, Some(rate));
    login_over(link, config(), user, key).await
}

async fn login_over(
    link: Link,
    config: russh::client::Config,
    user: &str,
    key: &PrivateKey,
) -> Result<Option<Handle<Trust>>, russh::Error> {
    let mut handle = russh::client::connect_stream(Arc::new(config), link, Trust).await?;
    let key = PrivateKeyWithHashAlg::new(Arc::new(key.clone()), None);
    let ok = handle.authenticate_publickey(user, key).await?;
    Ok(ok.success().then_some(handle))
}

/// A client's end of a connection whose reads stop while `frozen` is set, and take at most
/// `rate` bytes a second (a tenth of a second's worth at a time) when it has one.
struct Link {
    tcp: TcpStream,
    frozen: Arc<AtomicBool>,
    rate: Option<usize>,
    budget: usize,
    refill: Pin<Box<tokio::time::Sleep>>,
}

impl Link {
    fn new(tcp: TcpStream, rate: Option<usize>) -> Link {
        // As `config` asks of a connection russh makes itself.
        let _ = tcp.set_nodelay(true);
        Link {
            tcp,
            frozen: Arc::new(AtomicBool::new(false)),
            rate,
            budget: rate.map_or(0, |r| r / 10),
            refill: Box::pin(tokio::time::sleep(Duration::from_millis(100))),
        }
    }
}

impl AsyncRead for Link {
    fn poll_read(
        mut self: Pin<&mut Self>,
        cx: &mut Context<'_>,
        buf: &mut ReadBuf<'_>,
    ) -> Poll<std::io::Result<()>> {
        if self.frozen.load(Ordering::Relaxed) {
            return Poll::Pending;
        }
        let Some(rate) = self.rate else {
            return Pin::new(&mut self.tcp).poll_read(cx, buf);
        };
        if self.budget == 0 {
            if self.refill.as_mut().poll(cx).is_pending() {
                return Poll::Pending;
            }
            let next = tokio::time::Instant::now() + Duration::from_millis(100);
            self.refill.as_mut().reset(next);
            self.budget = rate / 10;
        }
        let n = self.budget.min(buf.remaining());
        let mut part = ReadBuf::new(buf.initialize_unfilled_to(n));
        let r = Pin::new(&mut self.tcp).poll_read(cx, &mut part);
        let got = part.filled().len();
        if r.is_ready() {
            buf.advance(got);
            self.budget -= got;
        }
        r
    }
}

impl AsyncWrite for Link {
    fn poll_write(
        mut self: Pin<&mut Self>,
        cx: &mut Context<'_>,
        buf: &[u8],
    ) -> Poll<std::io::Result<usize>> {
        Pin::new(&mut self.tcp).poll_write(cx, buf)
    }

    fn poll_flush(mut self: Pin<&mut Self>, cx: &mut Context<'_>) -> Poll<std::io::Result<()>> {
        Pin::new(&mut self.tcp).poll_flush(cx)
    }

    fn poll_shutdown(mut self: Pin<&mut Self>, cx: &mut Context<'_>) -> Poll<std::io::Result<()>> {
        Pin::new(&mut self.tcp).poll_shutdown(cx)
    }
}

/// A terminal on one session channel: what it has received so far.
pub struct Term {
    pub channel: russh::Channel<Msg>,
    /// The bytes received on the channel, in order.
    pub seen: Vec<u8>,
    /// What came on the error stream (a refusal's reason).
    pub errors: Vec<u8>,
    pub exit: Option<u32>,
    /// The server asked for the channel's request and refused it.
    pub refused: bool,
    pub closed: bool,
}

impl Term {
    /// A session channel with a PTY of `cols` × `rows` and a shell.
    pub async fn open(handle: &Handle<Trust>, cols: u32, rows: u32) -> Result<Term, russh::Error> {
        let channel = handle.channel_open_session().await?;
        channel
            .request_pty(true, "xterm-256color", cols, rows, 0, 0, &[])
            .await?;
        channel.request_shell(true).await?;
        Ok(Term::on(channel))
    }

    pub fn on(channel: russh::Channel<Msg>) -> Term {
        Term {
            channel,
            seen: vec![],
            errors: vec![],
            exit: None,
            refused: false,
            closed: false,
        }
    }

    pub async fn send(&self, bytes: &[u8]) -> Result<(), russh::Error> {
        self.channel.data(bytes).await
    }

    /// Reads until `needle` is among the bytes received from `from` on, the channel closes
    /// or `within` passes; whether it was found.
    pub async fn until(&mut self, from: usize, needle: &[u8], within: Duration) -> bool {
        let end = Instant::now() + within;
        loop {
            if self.seen[from.min(self.seen.len())..]
                .windows(needle.len())
                .any(|w| w == needle)
            {
                return true;
            }
            if self.closed || !self.next(end).await {
                return false;
            }
        }
    }

    /// Reads until the channel closes (or `within` passes); whether it closed.
    pub async fn until_closed(&mut self, within: Duration) -> bool {
        let end = Instant::now() + within;
        while !self.closed && self.next(end).await {}
        self.closed
    }

    /// One message, by `end`; false when none came.
    pub async fn next(&mut self, end: Instant) -> bool {
        let msg = match tokio::time::timeout_at(end, self.channel.wait()).await {
            Ok(Some(msg)) => msg,
            Ok(None) => {
                self.closed = true;
                return true;
            }
            Err(_) => return false,
        };
        match msg {
            ChannelMsg::Data { data } => self.seen.extend_from_slice(&data),
            ChannelMsg::ExtendedData { data, .. } => self.errors.extend_from_slice(&data),
            ChannelMsg::ExitStatus { exit_status } => self.exit = Some(exit_status),
            ChannelMsg::Failure => self.refused = true,
            ChannelMsg::Close => self.closed = true,
            _ => {}
        }
        true
    }
}

/// Waits up to `within` for `done`, checking every few milliseconds.
pub async fn eventually(within: Duration, mut done: impl FnMut() -> bool) -> bool {
    let end = Instant::now() + within;
    while Instant::now() < end {
        if done() {
            return true;
        }
        tokio::time::sleep(Duration::from_millis(20)).await;
    }
    done()
}
