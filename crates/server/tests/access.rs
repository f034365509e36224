//! Who may connect, over real handshakes on the loopback interface: a
//! foreign page's origin, `Origin: null` and a rebound host name are refused; the
//! server's own pages, allowed origins and non-browser clients are admitted; a token,
//! when required, must be presented.

use pliant_server::access::Access;
use pliant_server::session::SessionOptions;
use pliant_server::{start, RunningServer, ServerConfig, Session};
use tokio_tungstenite::tungstenite::client::IntoClientRequest;
use tokio_tungstenite::tungstenite::http::HeaderValue;
use tokio_tungstenite::tungstenite::Error;

async fn server(access: Access) -> RunningServer {
    let scene = pliant_scene::demo_scene().unwrap();
    let session = Session::start(&scene, SessionOptions::default()).unwrap();
    let config = ServerConfig {
        host: "127.0.0.1".into(),
        port: 0,
        access,
        ..Default::default()
    };
    start(session, &config).await.unwrap()
}

/// The HTTP status of a handshake to `/ws{query}` with the given headers (101: admitted).
async fn handshake(s: &RunningServer, query: &str, headers: &[(&'static str, String)]) -> u16 {
    let mut request = format!("{}{query}", s.ws_url())
        .into_client_request()
        .unwrap();
    for (name, value) in headers {
        request
            .headers_mut()
            .insert(*name, HeaderValue::from_str(value).unwrap());
    }
    match tokio_tungstenite::connect_async(request).await {
        Ok((_, response)) => response.status().as_u16(),
        Err(Error::Http(response)) => response.status().as_u16(),
        Err(e) => panic!("handshake failed otherwise: {e}"),
    }
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn loopback_admits_its_own_pages_and_scripts_and_refuses_foreign_origins() {
    let s = server(Access::local()).await;
    let own = format!("http://{}", s.addr);
    // a script (no Origin) and the server's own viewer page
    assert_eq!(handshake(&s, "", &[]).await, 101);
    assert_eq!(handshake(&s, "", &[("origin", own.clone())]).await, 101);
    // any other page the user visits, and sandboxed frames or files
    for origin in [
        "http://evil.example",
        "null",
        "http://127.0.0.1:1",
        "https://localhost",
    ] {
        assert_eq!(
            handshake(&s, "", &[("origin", origin.to_string())]).await,
            403,
            "{origin}"
        );
    }
    // DNS rebinding: a foreign name resolving to 127.0.0.1 is "same origin" but not loopback
    let port = s.addr.port();
    let rebound = [
        ("host", format!("evil.example:{port}")),
        ("origin", format!("http://evil.example:{port}")),
    ];
    assert_eq!(handshake(&s, "", &rebound).await, 403);
    assert_eq!(
        handshake(&s, "", &[("host", format!("localhost:{port}"))]).await,
        101
    );
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn an_allowed_origin_is_admitted() {
    let access = Access::for_host(
        "127.0.0.1",
        None,
        vec!["http://app.example:3000".to_string()],
    )
    .unwrap();
    let s = server(access).await;
    let ok = [("origin", "http://app.example:3000".to_string())];
    assert_eq!(handshake(&s, "", &ok).await, 101);
    let other = [("origin", "http://app.example:3001".to_string())];
    assert_eq!(handshake(&s, "", &other).await, 403);
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn a_required_token_must_be_presented() {
    let access = Access::for_host("127.0.0.1", Some("s3cret-token".into()), vec![]).unwrap();
    let s = server(access).await;
    assert_eq!(handshake(&s, "", &[]).await, 401);
    assert_eq!(handshake(&s, "?token=wrong-token1", &[]).await, 401);
    assert_eq!(handshake(&s, "?token=s3cret-token", &[]).await, 101);
    // the token does not excuse a foreign page
    let foreign = [("origin", "http://evil.example".to_string())];
    assert_eq!(handshake(&s, "?token=s3cret-token", &foreign).await, 403);
    // with a token, any host name may be used (the server is meant to be shared)
    let port = s.addr.port();
    let named = [("host", format!("workstation.lan:{port}"))];
    assert_eq!(handshake(&s, "?token=s3cret-token", &named).await, 101);
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn a_network_address_gets_a_generated_token() {
    let access = Access::for_host("0.0.0.0", None, vec![]).unwrap();
    let token = access.token().expect("a token for the network").to_string();
    let s = server(access).await;
    assert_eq!(handshake(&s, "", &[]).await, 401);
    assert_eq!(handshake(&s, &format!("?token={token}"), &[]).await, 101);
}

async fn server_with(config: ServerConfig) -> RunningServer {
    let scene = pliant_scene::demo_scene().unwrap();
    let session = Session::start(&scene, SessionOptions::default()).unwrap();
    start(session, &config).await.unwrap()
}

/// Sends `hello` and waits for the `welcome`.
async fn say_hello(
    ws: &mut tokio_tungstenite::WebSocketStream<
        tokio_tungstenite::MaybeTlsStream<tokio::net::TcpStream>,
    >,
) {
    use futures_util::{SinkExt, StreamExt};
    let hello = r#"{"type":"hello","version":1}"#;
    ws.send(tokio_tungstenite::tungstenite::Message::text(hello))
        .await
        .unwrap();
    while let Some(Ok(m)) = ws.next().await {
        if m.to_text().is_ok_and(|t| t.contains("\"welcome\"")) {
            return;
        }
    }
    panic!("no welcome");
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn a_connection_that_never_says_hello_is_closed() {
    use futures_util::StreamExt;
    let s = server_with(ServerConfig {
        host: "127.0.0.1".into(),
        port: 0,
        hello_timeout: std::time::Duration::from_millis(200),
        ..Default::default()
    })
    .await;
    let (mut silent, _) = tokio_tungstenite::connect_async(s.ws_url()).await.unwrap();
    // the server ends it: a close frame naming the reason, then the end of the stream
    let mut reason = None;
    while let Some(Ok(m)) = silent.next().await {
        if let tokio_tungstenite::tungstenite::Message::Close(Some(frame)) = m {
            reason = Some(frame.reason.to_string());
        }
    }
    assert!(reason.is_some_and(|r| r.contains("no hello")));
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn the_client_cap_refuses_the_next_until_one_leaves() {
    let s = server_with(ServerConfig {
        host: "127.0.0.1".into(),
        port: 0,
        max_clients: 2,
        ..Default::default()
    })
    .await;
    let (mut a, _) = tokio_tungstenite::connect_async(s.ws_url()).await.unwrap();
    let (mut b, _) = tokio_tungstenite::connect_async(s.ws_url()).await.unwrap();
    say_hello(&mut a).await;
    say_hello(&mut b).await;
    assert_eq!(handshake(&s, "", &[]).await, 503);
    a.close(None).await.unwrap();
    drop(a);
    // the slot comes back when the server has seen the close: wait for that condition
    let deadline = std::time::Instant::now() + std::time::Duration::from_secs(300);
    loop {
        match handshake(&s, "", &[]).await {
            101 => break,
            503 if std::time::Instant::now() < deadline => tokio::task::yield_now().await,
            other => panic!("handshake after a client left: {other}"),
        }
    }
}

/// Hardening item 7: a connection that sends half its request headers and then nothing is
/// closed by the server (after `HEADER_READ_TIMEOUT`); the wait is for the close itself.
#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn half_sent_headers_are_timed_out() {
    use tokio::io::{AsyncReadExt, AsyncWriteExt};
    let s = server_with(ServerConfig {
        host: "127.0.0.1".into(),
        port: 0,
        ..Default::default()
    })
    .await;
    let mut tcp = tokio::net::TcpStream::connect(s.addr).await.unwrap();
    tcp.write_all(b"GET / HTTP/1.1\r\nHost: 127.0.0.1\r\nX-Slow: ")
        .await
        .unwrap();
    // the server answers (408) or just closes; either way the stream ends
    let mut rest = Vec::new();
    let hang_guard = std::time::Duration::from_secs(300);
    let read = tokio::time::timeout(hang_guard, tcp.read_to_end(&mut rest)).await;
    assert!(
        read.is_ok(),
        "the half-sent request was still open after {hang_guard:?}"
    );
    let text = String::from_utf8_lossy(&rest);
    assert!(
        rest.is_empty() || text.starts_with("HTTP/1.1 408"),
        "{text}"
    );
}

/// Sockets that never say `hello` hold no client slot — a local process that
/// keeps connecting without greeting locks no viewer out. With a cap of 2, ten silent
/// connections leave both slots to viewers; a third viewer's `hello` is refused with
/// `server_full` (and the next handshake with 503) until one leaves.
#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn sockets_that_never_greet_hold_no_client_slot() {
    use futures_util::{SinkExt, StreamExt};
    use tokio_tungstenite::tungstenite::Message;
    let s = server_with(ServerConfig {
        host: "127.0.0.1".into(),
        port: 0,
        max_clients: 2,
        ..Default::default()
    })
    .await;
    let mut silent = Vec::new();
    for _ in 0..10 {
        silent.push(
            tokio_tungstenite::connect_async(s.ws_url())
                .await
                .unwrap()
                .0,
        );
    }
    let (mut a, _) = tokio_tungstenite::connect_async(s.ws_url()).await.unwrap();
    let (mut b, _) = tokio_tungstenite::connect_async(s.ws_url()).await.unwrap();
    let (mut c, _) = tokio_tungstenite::connect_async(s.ws_url()).await.unwrap();
    say_hello(&mut a).await;
    say_hello(&mut b).await;
    // the third greets too late: refused, its connection open
    c.send(Message::text(r#"{"type":"hello","version":1}"#))
        .await
        .unwrap();
    let refused = loop {
        match c.next().await {
            Some(Ok(Message::Text(t))) => break t.to_string(),
            Some(Ok(_)) => continue,
            other => panic!("no reply to hello: {other:?}"),
        }
    };
    assert!(
        refused.contains("server_full") && refused.contains("--max-clients"),
        "{refused}"
    );
    assert_eq!(handshake(&s, "", &[]).await, 503);
    drop(silent);
}
