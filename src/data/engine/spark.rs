//! The Spark Connect protocol, as much of it as a query needs: one SQL relation sent as the plan
//! of an `ExecutePlan` call (gRPC, server streaming), and the Arrow IPC batches of its answer
//! read back into one frame.
//!
//! The messages are the subset of Spark's `spark/connect/base.proto` and `relations.proto`
//! (Spark 3.4 to 4.x) that this uses, written with their field numbers; fields a message has and
//! these leave out are skipped when decoding, as protobuf does.

use std::io::Cursor;
use std::time::Duration;

use polars::prelude::*;
use polars_arrow::io::ipc::read::{StreamReader, StreamState, read_stream_metadata};
use tonic::codegen::http::uri::PathAndQuery;

use super::{EngineError, EngineUrl};

/// `ExecutePlanRequest`: a plan to run in a session.
#[derive(Clone, PartialEq, prost::Message)]
struct ExecutePlanRequest {
    #[prost(string, tag = "1")]
    session_id: String,
    #[prost(message, optional, tag = "2")]
    user_context: Option<UserContext>,
    #[prost(message, optional, tag = "3")]
    plan: Option<Plan>,
    #[prost(string, optional, tag = "4")]
    client_type: Option<String>,
}

/// `UserContext`: who runs the session.
#[derive(Clone, PartialEq, prost::Message)]
struct UserContext {
    #[prost(string, tag = "1")]
    user_id: String,
    #[prost(string, tag = "2")]
    user_name: String,
}

/// `Plan`, with its `root` relation.
#[derive(Clone, PartialEq, prost::Message)]
struct Plan {
    #[prost(message, optional, tag = "1")]
    root: Option<Relation>,
}

/// `Relation`, of the one kind sent here: `sql`.
#[derive(Clone, PartialEq, prost::Message)]
struct Relation {
    #[prost(message, optional, tag = "10")]
    sql: Option<Sql>,
}

/// `SQL`: a query text.
#[derive(Clone, PartialEq, prost::Message)]
struct Sql {
    #[prost(string, tag = "1")]
    query: String,
}

/// `ExecutePlanResponse`: one message of the answer stream; only Arrow batches are read.
#[derive(Clone, PartialEq, prost::Message)]
struct ExecutePlanResponse {
    #[prost(message, optional, tag = "2")]
    arrow_batch: Option<ArrowBatch>,
}

/// `ExecutePlanResponse.ArrowBatch`: rows as an Arrow IPC stream.
#[derive(Clone, PartialEq, prost::Message)]
struct ArrowBatch {
    #[prost(int64, tag = "1")]
    row_count: i64,
    #[prost(bytes = "vec", tag = "2")]
    data: Vec<u8>,
}

/// How long connecting may take before the engine counts as unreachable.
const CONNECT_TIMEOUT: Duration = Duration::from_secs(10);

/// Run `query` on the Spark Connect server `url`, waiting at most `timeout` for the whole
/// answer; its rows as one frame.
pub fn run(url: &EngineUrl, query: &str, timeout: Duration) -> Result<DataFrame, EngineError> {
    let runtime = tokio::runtime::Builder::new_current_thread()
        .enable_all()
        .build()
        .map_err(|e| EngineError::new(url, query, format!("cannot start the network runtime: {e}")))?;
    let batches = runtime.block_on(async {
        let settled_then_run = async {
            // A failure here is the query's: it names the query the user asked for.
            settle_session(url).await.map_err(|e| EngineError::new(url, query, e.message))?;
            execute(url, query).await
        };
        tokio::time::timeout(timeout, settled_then_run).await.map_err(|_| {
            EngineError::new(url, query, format!("no complete answer within {} s", timeout.as_secs_f64()))
        })?
    })?;
    frame_of(&batches).map_err(|e| EngineError::new(url, query, format!("unreadable answer: {e}")))
}

/// What this process's session sets before its first query on an engine.
///
/// Spark's Parquet reader takes a column chunk whose statistics give a null count but no minimum
/// and maximum (polars writes such chunks for float columns that hold NaN) for one holding only
/// nulls, so a filter on that column drops the chunk's rows without a word (`x IS NOT NULL`
/// gave 0 of 120,000 rows here). Without row-group filtering every chunk is read and filtered
/// row by row: slower for a selective filter, never wrong.
const SESSION_SETTINGS: &str = "SET spark.sql.parquet.filterPushdown=false";

/// Apply [`SESSION_SETTINGS`] once per engine and process (the session outlives the query).
async fn settle_session(url: &EngineUrl) -> Result<(), EngineError> {
    static SETTLED: std::sync::Mutex<Vec<String>> = std::sync::Mutex::new(Vec::new());
    let key = url.to_string();
    if SETTLED.lock().is_ok_and(|done| done.contains(&key)) {
        return Ok(());
    }
    execute(url, SESSION_SETTINGS).await?;
    if let Ok(mut done) = SETTLED.lock() {
        done.push(key);
    }
    Ok(())
}

/// Send the query and gather the Arrow data of every batch of the answer.
async fn execute(url: &EngineUrl, query: &str) -> Result<Vec<Vec<u8>>, EngineError> {
    let fail = |message: String| EngineError::new(url, query, message);
    let endpoint = tonic::transport::Endpoint::from_shared(format!("http://{}:{}", url.host, url.port))
        .map_err(|e| fail(format!("not a usable address: {e}")))?
        .connect_timeout(CONNECT_TIMEOUT);
    let channel = endpoint.connect().await.map_err(|e| fail(connect_failure(&e)))?;
    let mut grpc = tonic::client::Grpc::new(channel);
    grpc.ready().await.map_err(|e| fail(format!("the connection is not ready: {e}")))?;
    let request = ExecutePlanRequest {
        session_id: session_id(),
        user_context: Some(UserContext { user_id: url.user.clone(), user_name: url.user.clone() }),
        plan: Some(Plan { root: Some(Relation { sql: Some(Sql { query: query.to_string() }) }) }),
        client_type: Some(format!("dataink/{}", env!("CARGO_PKG_VERSION"))),
    };
    let mut request = tonic::Request::new(request);
    if let Some(token) = &url.token {
        let value = format!("Bearer {token}")
            .parse()
            .map_err(|_| fail("the token holds characters a header cannot carry".to_string()))?;
        request.metadata_mut().insert("authorization", value);
    }
    let path = PathAndQuery::from_static("/spark.connect.SparkConnectService/ExecutePlan");
    let codec = tonic_prost::ProstCodec::<ExecutePlanRequest, ExecutePlanResponse>::default();
    let mut stream =
        grpc.server_streaming(request, path, codec).await.map_err(|s| fail(status_message(&s)))?.into_inner();
    let mut batches = Vec::new();
    while let Some(message) = stream.message().await.map_err(|s| fail(status_message(&s)))? {
        if let Some(batch) = message.arrow_batch {
            batches.push(batch.data);
        }
    }
    Ok(batches)
}

/// The session id of this process's queries: one session on the server per process, not one
/// per query (a session lives on the server until it has been idle for a while).
fn session_id() -> String {
    static SESSION: std::sync::OnceLock<String> = std::sync::OnceLock::new();
    SESSION.get_or_init(new_session_id).clone()
}

/// A session id in the UUID form the server asks for.
fn new_session_id() -> String {
    use std::time::{SystemTime, UNIX_EPOCH};
    let nanos = SystemTime::now().duration_since(UNIX_EPOCH).map_or(0, |d| d.as_nanos());
    let mixed = nanos ^ (u128::from(std::process::id()) << 64);
    let hex = format!("{mixed:032x}");
    format!("{}-{}-4{}-8{}-{}", &hex[0..8], &hex[8..12], &hex[13..16], &hex[17..20], &hex[20..32])
}

/// Why connecting failed, in words: the innermost cause (connection refused, no such host).
fn connect_failure(error: &tonic::transport::Error) -> String {
    let mut cause: &dyn std::error::Error = error;
    while let Some(inner) = cause.source() {
        cause = inner;
    }
    format!("cannot connect ({cause}); is a Spark Connect server listening there?")
}

/// The server's answer to a failed call, by what it means to the user.
fn status_message(status: &tonic::Status) -> String {
    use tonic::Code;
    let said = status.message().lines().next().unwrap_or("").trim();
    match status.code() {
        Code::Unauthenticated | Code::PermissionDenied => {
            format!("the engine refused the credentials ({said}); give `token` in the engine URL")
        }
        Code::Unavailable => format!("the engine is unavailable ({said})"),
        Code::DeadlineExceeded => format!("the engine gave up waiting ({said})"),
        _ => format!("the engine reported: {said}"),
    }
}

/// The Arrow IPC streams of the batches, as one frame (each batch is a whole stream, its schema
/// first).
fn frame_of(batches: &[Vec<u8>]) -> PolarsResult<DataFrame> {
    let mut fields = None;
    let mut columns: Vec<Vec<Box<dyn polars_arrow::array::Array>>> = Vec::new();
    for data in batches {
        let mut cursor = Cursor::new(data.as_slice());
        let metadata = read_stream_metadata(&mut cursor)?;
        let schema: Vec<ArrowField> = metadata.schema.iter_values().cloned().collect();
        if columns.is_empty() {
            columns = vec![Vec::new(); schema.len()];
        }
        fields.get_or_insert(schema);
        for state in StreamReader::new(cursor, metadata, None) {
            if let StreamState::Some(batch) = state? {
                for (column, array) in columns.iter_mut().zip(batch.into_arrays()) {
                    column.push(array);
                }
            }
        }
    }
    let Some(fields) = fields else { return DataFrame::new(0, Vec::new()) };
    let series: Vec<Column> = fields
        .iter()
        .zip(columns)
        .map(|(field, arrays)| {
            if arrays.is_empty() {
                Ok(Series::new_empty(field.name.clone(), &DataType::from_arrow_field(field)).into())
            } else {
                Series::try_from((field, arrays)).map(Column::from)
            }
        })
        .collect::<PolarsResult<_>>()?;
    DataFrame::new_infer_height(series)
}
