"""Whether a run directory holds a complete run: run.json's status (README.md, "Run directory").
Only a run whose launcher saw every role exit 0 and every output written says "complete"; a failed,
interrupted or still running one, and one whose run.json is missing or has no status (written by a
wsntrack from before the status existed: whether it finished cannot be told), is incomplete."""

import json

from .tables import InputError


def run_status(run_dir):
    """(status, reason) of run_dir/run.json: status is "complete", "failed", "running", or None
    when run.json has none; reason the failure's one line, or a description of what is missing."""
    path = run_dir / "run.json"
    try:
        data = json.loads(path.read_text(encoding="utf-8"))
    except FileNotFoundError:
        return None, "no run.json: no run was started here, or its launcher stopped before writing it"
    except (OSError, UnicodeDecodeError, json.JSONDecodeError) as error:
        return None, f"run.json cannot be read ({error})"
    if not isinstance(data, dict) or "status" not in data:
        return None, "run.json has no status: written by a wsntrack from before runs were marked complete"
    status, reason = data.get("status"), data.get("reason")
    if status == "running":
        reason = reason or "its launcher has not finished, or was killed before it could mark the run"
    return status, reason or ""


def incomplete_reason(run_dir):
    """None for a complete run, else "incomplete run (status S: REASON)" without the directory."""
    status, reason = run_status(run_dir)
    if status == "complete":
        return None
    return f"incomplete run (status {status or 'missing'}: {reason})"


def require_complete(run_dir):
    """Raises InputError "RUN_DIR: incomplete run (status failed: REASON)" unless the run is complete."""
    why = incomplete_reason(run_dir)
    if why:
        raise InputError(f"{run_dir}: {why}")
