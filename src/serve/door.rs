//! Who waits at the door: connections not logged in (bounded by address and in all, apart from
//! the class's sessions) and connections logged in without an explorer (bounded, and closed after
//! a grace time by their connection). When the room for either is full, a newcomer is let in and
//! the oldest connection of the address holding the most makes room: a flood from a few addresses
//! closes only its own, and the teacher, from an address of their own, always gets to the
//! password prompt. (sshd's MaxStartups refuses newcomers at random instead, the teacher among
//! them.)

use std::collections::HashMap;
use std::net::IpAddr;
use std::sync::{Arc, Mutex};
use tokio::sync::Notify;

/// The door's bounds (from [`super::Limits`]).
#[derive(Clone, Copy, Debug)]
pub struct Bounds {
    /// Connections not logged in, in all.
    pub waiting: usize,
    /// Connections not logged in, from one address.
    pub per_address: usize,
    /// Connections logged in without an explorer.
    pub idle: usize,
}

#[derive(Default)]
struct Rooms {
    next: u64,
    /// Not logged in.
    waiting: HashMap<u64, Entry>,
    /// Logged in, no explorer yet.
    idle: HashMap<u64, Entry>,
}

struct Entry {
    ip: IpAddr,
    /// Told to go when another needs its place.
    go: Arc<Notify>,
}

pub struct Door {
    bounds: Bounds,
    rooms: Mutex<Rooms>,
}

/// One connection's place at the door, given up when dropped.
pub struct Pass {
    door: Arc<Door>,
    id: u64,
    /// Notified when the connection must close to make room.
    pub go: Arc<Notify>,
}

impl Door {
    pub fn new(bounds: Bounds) -> Door {
        Door {
            bounds,
            rooms: Mutex::default(),
        }
    }

    /// A place for a connection from `ip` (the oldest of the address holding the most
    /// waiting makes room); None when `ip` already holds its share.
    pub fn arrive(self: &Arc<Door>, ip: IpAddr) -> Option<Pass> {
        let mut rooms = super::lock(&self.rooms);
        let from_ip = rooms.waiting.values().filter(|e| e.ip == ip).count();
        if from_ip >= self.bounds.per_address.max(1) {
            return None;
        }
        if rooms.waiting.len() >= self.bounds.waiting.max(1) {
            make_room(&mut rooms.waiting, None);
        }
        rooms.next += 1;
        let id = rooms.next;
        let go = Arc::new(Notify::new());
        let entry = Entry {
            ip,
            go: Arc::clone(&go),
        };
        rooms.waiting.insert(id, entry);
        Some(Pass {
            door: Arc::clone(self),
            id,
            go,
        })
    }

    /// Connections at the door now: not logged in, and logged in without an explorer.
    pub fn count(&self) -> (usize, usize) {
        let rooms = super::lock(&self.rooms);
        (rooms.waiting.len(), rooms.idle.len())
    }
}

/// Tells the oldest connection of the address holding the most in `room` (other than `keep`)
/// to go, and takes it out.
fn make_room(room: &mut HashMap<u64, Entry>, keep: Option<u64>) {
    let mut by_ip: HashMap<IpAddr, (usize, u64)> = HashMap::new();
    for (&id, e) in room.iter().filter(|(id, _)| Some(**id) != keep) {
        let (n, oldest) = by_ip.entry(e.ip).or_insert((0, id));
        *n += 1;
        *oldest = (*oldest).min(id);
    }
    // The most held; among equals, the oldest connection.
    let victim = by_ip
        .values()
        .max_by_key(|&&(n, oldest)| (n, std::cmp::Reverse(oldest)))
        .map(|&(_, oldest)| oldest);
    if let Some(e) = victim.and_then(|id| room.remove(&id)) {
        e.go.notify_one();
    }
}

impl Pass {
    /// Logged in: out of the waiting room, into the room of those without an explorer (the
    /// oldest there making room when it is full).
    pub fn logged_in(&self) {
        let mut rooms = super::lock(&self.door.rooms);
        let Some(entry) = rooms.waiting.remove(&self.id) else {
            return;
        };
        if rooms.idle.len() >= self.door.bounds.idle.max(1) {
            make_room(&mut rooms.idle, Some(self.id));
        }
        rooms.idle.insert(self.id, entry);
    }

    /// Its explorer started: counted among the sessions from now on.
    pub fn seated(&self) {
        let mut rooms = super::lock(&self.door.rooms);
        rooms.idle.remove(&self.id);
        rooms.waiting.remove(&self.id);
    }
}

impl Drop for Pass {
    fn drop(&mut self) {
        let mut rooms = super::lock(&self.door.rooms);
        rooms.waiting.remove(&self.id);
        rooms.idle.remove(&self.id);
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn ip(n: u8) -> IpAddr {
        IpAddr::from([10, 0, 0, n])
    }

    /// A flood from a few addresses takes their own places, never a newcomer's.
    #[test]
    fn a_newcomer_always_gets_in_and_the_heaviest_address_makes_room() {
        let door = Arc::new(Door::new(Bounds {
            waiting: 6,
            per_address: 3,
            idle: 2,
        }));
        let mut flood: Vec<Pass> = (0..3).filter_map(|_| door.arrive(ip(1))).collect();
        assert!(door.arrive(ip(1)).is_none(), "past its share");
        flood.extend((0..2).filter_map(|_| door.arrive(ip(2))));
        let c = door.arrive(ip(3)).unwrap();
        assert_eq!(door.count(), (6, 0));
        // Full: the next newcomer is in, and ip(1)'s oldest was told to go.
        let teacher = door.arrive(ip(4)).unwrap();
        assert_eq!(door.count(), (6, 0));
        assert!(told(&flood[0]) && !told(&flood[1]) && !told(&flood[3]));
        assert!(!told(&c));
        // Logged in: out of the waiting room; the idle room makes room in turn (its oldest).
        c.logged_in();
        flood[3].logged_in();
        teacher.logged_in();
        assert_eq!(door.count(), (3, 2));
        assert!(told(&flood[3]) && !told(&teacher) && !told(&c));
        teacher.seated();
        assert_eq!(door.count(), (3, 1));
        drop(flood);
        assert_eq!(door.count(), (0, 1));
        drop(c);
        assert_eq!(door.count(), (0, 0));
    }

    fn told(p: &Pass) -> bool {
        use std::future::Future;
        let notified = p.go.notified();
        tokio::pin!(notified);
        // A stored permit makes the first poll ready; re-store it for the next look.
        let ready = notified
            .as_mut()
            .poll(&mut std::task::Context::from_waker(std::task::Waker::noop()))
            .is_ready();
        if ready {
            p.go.notify_one();
        }
        ready
    }
}
