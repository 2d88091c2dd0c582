//! A request's spec and data files: the body as TOML text, or a `multipart/form-data` form with
//! a `spec` field and one field per data file (its file name is the path the spec gives).

use axum::body::Bytes;
use axum::extract::{FromRequest, Multipart, Request};
use axum::http::{StatusCode, header};

use super::Limits;
use super::reply::Problem;

/// What a request sent.
#[derive(Debug)]
pub struct Submitted {
    /// The spec's text.
    pub spec: String,
    /// Uploaded data files by name, in the order sent (names are plain file names).
    pub files: Vec<(String, Bytes)>,
}

/// Read the spec (and files) from `request`, within `limits`.
pub async fn read(request: Request, limits: &Limits) -> Result<Submitted, Problem> {
    let multipart = request
        .headers()
        .get(header::CONTENT_TYPE)
        .and_then(|v| v.to_str().ok())
        .is_some_and(|v| v.to_ascii_lowercase().starts_with("multipart/form-data"));
    let submitted = if multipart { read_form(request, limits).await? } else { read_text(request, limits).await? };
    if submitted.spec.len() > limits.spec_bytes {
        return Err(Problem::new(
            StatusCode::PAYLOAD_TOO_LARGE,
            format!("the spec has {} bytes; this server reads at most {}", submitted.spec.len(), limits.spec_bytes),
        ));
    }
    Ok(submitted)
}

async fn read_text(request: Request, limits: &Limits) -> Result<Submitted, Problem> {
    let body = axum::body::to_bytes(request.into_body(), limits.upload_bytes).await.map_err(|_| too_large(limits))?;
    let spec = String::from_utf8(body.to_vec())
        .map_err(|_| Problem::new(StatusCode::BAD_REQUEST, "the body is not UTF-8 text; send the spec as TOML text"))?;
    Ok(Submitted { spec, files: Vec::new() })
}

async fn read_form(request: Request, limits: &Limits) -> Result<Submitted, Problem> {
    let mut form = Multipart::from_request(request, &())
        .await
        .map_err(|e| Problem::new(StatusCode::BAD_REQUEST, format!("unreadable form: {}", e.body_text())))?;
    let mut spec = None;
    let mut files = Vec::new();
    loop {
        let field = match form.next_field().await {
            Ok(Some(field)) => field,
            Ok(None) => break,
            Err(e) if e.status() == StatusCode::PAYLOAD_TOO_LARGE => return Err(too_large(limits)),
            Err(e) => return Err(Problem::new(StatusCode::BAD_REQUEST, format!("unreadable form: {}", e.body_text()))),
        };
        let name = field.name().unwrap_or_default().to_string();
        let file_name = field.file_name().map(str::to_string);
        let bytes = field.bytes().await.map_err(|e| {
            if e.status() == StatusCode::PAYLOAD_TOO_LARGE {
                too_large(limits)
            } else {
                Problem::new(StatusCode::BAD_REQUEST, format!("unreadable form field `{name}`: {}", e.body_text()))
            }
        })?;
        if name == "spec" {
            let text = String::from_utf8(bytes.to_vec())
                .map_err(|_| Problem::new(StatusCode::BAD_REQUEST, "the `spec` field is not UTF-8 text"))?;
            spec = Some(text);
            continue;
        }
        let file = file_name.unwrap_or(name);
        check_file_name(&file)?;
        if files.iter().any(|(f, _)| *f == file) {
            return Err(Problem::new(StatusCode::BAD_REQUEST, format!("the file `{file}` is sent twice")));
        }
        if files.len() == limits.files {
            return Err(Problem::new(
                StatusCode::PAYLOAD_TOO_LARGE,
                format!("more than {} files in one request", limits.files),
            ));
        }
        if let Some((other, _)) = files.iter().find(|(f, _): &&(String, Bytes)| inside(f, &file) || inside(&file, f)) {
            return Err(Problem::new(
                StatusCode::BAD_REQUEST,
                format!("`{other}` and `{file}` cannot both be sent: one would be a folder holding the other"),
            ));
        }
        files.push((file, bytes));
    }
    let spec = spec.ok_or_else(|| Problem::new(StatusCode::BAD_REQUEST, "the form has no `spec` field"))?;
    Ok(Submitted { spec, files })
}

/// An uploaded file's name is a relative path of plain names (as a spec names its data, e.g.
/// `data/cars.json`): no `..`, no absolute path, nothing hidden, no control characters, at most
/// 8 levels and 255 bytes.
pub fn check_file_name(name: &str) -> Result<(), Problem> {
    let parts: Vec<&str> = name.split('/').collect();
    let plain = |part: &&str| {
        !part.is_empty() && !part.starts_with('.') && !part.chars().any(|c| c == '\\' || c == ':' || c.is_control())
    };
    if name.len() <= 255 && parts.len() <= 8 && parts.iter().all(plain) {
        Ok(())
    } else {
        Err(Problem::new(
            StatusCode::BAD_REQUEST,
            format!(
                "the file name {:?} is not a relative path of plain names; send files as `name.csv` or `data/name.csv`",
                crate::visible::single_line(name)
            ),
        ))
    }
}

/// Whether `name` would be a file inside the folder `folder`.
fn inside(name: &str, folder: &str) -> bool {
    name.strip_prefix(folder).is_some_and(|rest| rest.starts_with('/'))
}

fn too_large(limits: &Limits) -> Problem {
    Problem::new(
        StatusCode::PAYLOAD_TOO_LARGE,
        format!("the request is larger than this server's limit of {} bytes", limits.upload_bytes),
    )
}
