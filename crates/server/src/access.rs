//! Who may open the WebSocket: local by default, safe when shared.
//!
//! * **Origin.** A browser sends the page's `Origin` with every WebSocket handshake, and
//!   any page the user visits may try `ws://127.0.0.1:8080/ws`. The handshake is accepted
//!   only from the server's own pages (the origin the browser used to reach it, i.e.
//!   `http://` or `https://` + the `Host` header) and from origins on the allow-list.
//!   `Origin: null` (sandboxed frames, files) is refused. A client that sends no `Origin`
//!   is not a web page (Python, scripts, tests) and passes this check.
//! * **Host (DNS rebinding).** Without a token, the `Host` header must name a loopback
//!   address (`localhost`, `127.x.x.x`, `[::1]`): otherwise a page on a domain that
//!   resolves to 127.0.0.1 would be "same-origin".
//! * **Token.** A server bound to anything but loopback requires a token (generated and
//!   printed with the URL unless given, as Jupyter does); the viewer passes it on from its
//!   page URL as `/ws?token=…`. A token can be required on loopback too.

use std::net::IpAddr;

/// The connection rules of one server.
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct Access {
    /// Required as `?token=` on `/ws` when set.
    token: Option<String>,
    /// Origins accepted besides the server's own (exact, e.g. `http://app.example:3000`).
    allowed_origins: Vec<String>,
}

/// Why a handshake was refused (the HTTP status and the text the client sees).
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum Refusal {
    /// 403: the page's origin may not connect.
    Origin(String),
    /// 403: a tokenless connection through a non-loopback host name.
    Host(String),
    /// 401: the token is missing or wrong.
    Token,
}

impl Refusal {
    pub fn status(&self) -> u16 {
        match self {
            Refusal::Origin(_) | Refusal::Host(_) => 403,
            Refusal::Token => 401,
        }
    }

    pub fn message(&self) -> String {
        match self {
            Refusal::Origin(o) => format!(
                "origin {o} may not connect to this Pliant server (allow it with --allow-origin)"
            ),
            Refusal::Host(h) => format!(
                "host {h} is not a loopback address: connect through 127.0.0.1 or localhost, or start the server with a token"
            ),
            Refusal::Token => {
                "missing or wrong token: open the URL `pliant serve` printed (it carries ?token=…)"
                    .into()
            }
        }
    }
}

/// Whether `host` (a bind address or a `Host` header's name, without port) is loopback.
pub fn is_loopback(host: &str) -> bool {
    let name = host.trim_start_matches('[').trim_end_matches(']');
    name.eq_ignore_ascii_case("localhost")
        || name.parse::<IpAddr>().is_ok_and(|ip| ip.is_loopback())
}

/// The host name of a `Host` header value (`name:port`, `[v6]:port`, `name`).
fn host_name(header: &str) -> &str {
    if let Some(rest) = header.strip_prefix('[') {
        return rest.split(']').next().unwrap_or(rest);
    }
    header.rsplit_once(':').map_or(header, |(name, _)| name)
}

/// A fresh random token: 128 bits from the operating system, as 32 hex digits.
pub fn generate_token() -> Result<String, String> {
    let mut bytes = [0u8; 16];
    getrandom::fill(&mut bytes).map_err(|e| format!("no random numbers for a token: {e}"))?;
    Ok(bytes.iter().map(|b| format!("{b:02x}")).collect())
}

/// Equal strings, compared in time independent of where they first differ.
fn same_secret(a: &str, b: &str) -> bool {
    a.len() == b.len()
        && a.bytes()
            .zip(b.bytes())
            .fold(0u8, |acc, (x, y)| acc | (x ^ y))
            == 0
}

impl Access {
    /// Loopback only, no token, no other origins.
    pub fn local() -> Self {
        Self::default()
    }

    /// The rules for a server bound to `host`: `token` if given, else a generated one when
    /// `host` is not loopback; `allowed_origins` besides the server's own.
    pub fn for_host(
        host: &str,
        token: Option<String>,
        allowed_origins: Vec<String>,
    ) -> Result<Self, String> {
        let token = match token {
            Some(t) if t.len() < 8 || !t.bytes().all(|b| b.is_ascii_alphanumeric() || b"-_.".contains(&b)) => {
                return Err(
                    "--token: at least 8 characters, letters, digits, '-', '_' and '.' only (it travels in the URL)"
                        .into(),
                )
            }
            Some(t) => Some(t),
            None if is_loopback(host) => None,
            None => Some(generate_token()?),
        };
        for o in &allowed_origins {
            if !(o.starts_with("http://") || o.starts_with("https://")) || o.ends_with('/') {
                return Err(format!(
                    "--allow-origin {o}: an origin is scheme://host[:port], e.g. http://app.example:3000"
                ));
            }
        }
        Ok(Self {
            token,
            allowed_origins,
        })
    }

    /// The token clients must present, if any.
    pub fn token(&self) -> Option<&str> {
        self.token.as_deref()
    }

    /// Checks one handshake: its `Origin` and `Host` headers and the `token` query value.
    pub fn check(
        &self,
        origin: Option<&str>,
        host: Option<&str>,
        token: Option<&str>,
    ) -> Result<(), Refusal> {
        if let Some(origin) = origin {
            let own = host.is_some_and(|h| {
                origin == format!("http://{h}") || origin == format!("https://{h}")
            });
            if !own && !self.allowed_origins.iter().any(|o| o == origin) {
                return Err(Refusal::Origin(origin.to_string()));
            }
        }
        match &self.token {
            Some(expected) => {
                if !token.is_some_and(|t| same_secret(t, expected)) {
                    return Err(Refusal::Token);
                }
            }
            None => {
                let name = host.map(host_name).unwrap_or("");
                if !is_loopback(name) {
                    return Err(Refusal::Host(name.to_string()));
                }
            }
        }
        Ok(())
    }
}

/// The `token` parameter of a query string (`a=1&token=abc`). No percent-decoding is
/// needed: tokens are limited to characters that URLs carry as they are.
pub fn token_in_query(query: Option<&str>) -> Option<&str> {
    query?
        .split('&')
        .find_map(|pair| pair.strip_prefix("token="))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn loopback_names() {
        for h in [
            "127.0.0.1",
            "localhost",
            "::1",
            "[::1]",
            "127.3.2.1",
            "LOCALHOST",
        ] {
            assert!(is_loopback(h), "{h}");
        }
        for h in [
            "0.0.0.0",
            "192.168.1.4",
            "evil.example",
            "",
            "localhost.evil.example",
        ] {
            assert!(!is_loopback(h), "{h}");
        }
        assert_eq!(host_name("127.0.0.1:8080"), "127.0.0.1");
        assert_eq!(host_name("[::1]:8080"), "::1");
        assert_eq!(host_name("localhost"), "localhost");
    }

    #[test]
    fn tokens_are_fresh_and_long() {
        let (a, b) = (generate_token().unwrap(), generate_token().unwrap());
        assert_eq!(a.len(), 32);
        assert_ne!(a, b);
        assert!(same_secret(&a, &a.clone()) && !same_secret(&a, &b) && !same_secret(&a, ""));
    }

    #[test]
    fn a_network_address_gets_a_token_and_loopback_none() {
        assert!(Access::for_host("0.0.0.0", None, vec![])
            .unwrap()
            .token()
            .is_some());
        assert!(Access::for_host("127.0.0.1", None, vec![])
            .unwrap()
            .token()
            .is_none());
        let given = Access::for_host("127.0.0.1", Some("abc-1234".into()), vec![]).unwrap();
        assert_eq!(given.token(), Some("abc-1234"));
        assert!(Access::for_host("0.0.0.0", Some(" ".into()), vec![]).is_err());
        assert!(Access::for_host("0.0.0.0", Some("short".into()), vec![]).is_err());
        assert!(Access::for_host("0.0.0.0", Some("with&amp=x".into()), vec![]).is_err());
        assert!(Access::for_host("::1", None, vec!["app.example".into()]).is_err());
    }

    #[test]
    fn query_token() {
        assert_eq!(token_in_query(Some("token=abc")), Some("abc"));
        assert_eq!(token_in_query(Some("x=1&token=abc")), Some("abc"));
        assert_eq!(token_in_query(Some("x=1")), None);
        assert_eq!(token_in_query(None), None);
    }
}
