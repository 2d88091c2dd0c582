#!/usr/bin/env bash
# Local multi-process Spark cluster + Spark Connect server, from PyPI's pyspark.
#
#   spark_cluster.sh install        pip-install pyspark (pinned) if not importable
#   spark_cluster.sh start DIR      master + 2 workers (1 core, 1g each) + Connect server,
#                                   all on 127.0.0.1; writes sc://127.0.0.1:PORT to DIR/connect_url;
#                                   returns once Connect accepts connections and 2 executors registered
#   spark_cluster.sh stop DIR       stop everything started from DIR (incl. executor JVMs)
#   spark_cluster.sh executors DIR  PIDs of the executor JVMs (CoarseGrainedExecutorBackend), one a line
#
# Optional env: PYTHON (default python3), SPARK_START_TIMEOUT (s, default 180), and fixed ports
# SC_MASTER_PORT, SC_MASTER_UI_PORT, SC_CONNECT_PORT, SC_CONNECT_UI_PORT (default: free ports).
set -euo pipefail

PYSPARK_VERSION=4.3.0
PY=${PYTHON:-python3}
CMD=${1:-}; DIR_ARG=${2:-}

die() { echo "spark_cluster: $*" >&2; exit 1; }
usage() { die "usage: $0 install | start DIR | stop DIR | executors DIR"; }

install() {   # any importable pyspark 4.x will do; otherwise install the pinned one
  "$PY" -c 'import pyspark, sys; sys.exit(not pyspark.__version__.startswith("4."))' 2>/dev/null && return 0
  PIP_ROOT_USER_ACTION=ignore "$PY" -m pip install -q --disable-pip-version-check "pyspark==$PYSPARK_VERSION"
}

# Common environment: SPARK_HOME is the pyspark package dir (it ships bin/, sbin/, jars/);
# everything writable lives under DIR.
setup_env() {
  [ -n "$DIR_ARG" ] || usage
  [ "$CMD" = start ] && mkdir -p "$DIR_ARG"
  [ -d "$DIR_ARG" ] || exit 0            # stop/executors on a DIR never started: nothing to do
  DIR=$(cd "$DIR_ARG" && pwd)
  [[ $DIR != *[[:space:]]* ]] || die "DIR must not contain whitespace (Spark's launch scripts split it)"
  export SPARK_HOME
  SPARK_HOME=$("$PY" -c 'import os, pyspark; print(os.path.dirname(pyspark.__file__))') \
    || die "pyspark not importable; run '$0 install' first"
  export SPARK_LOG_DIR=$DIR/logs SPARK_PID_DIR=$DIR/pids SPARK_WORKER_DIR=$DIR/work \
         SPARK_LOCAL_DIRS=$DIR/local SPARK_CONF_DIR=$DIR/conf \
         SPARK_LOCAL_IP=127.0.0.1 SPARK_LOCAL_HOSTNAME=127.0.0.1 \
         SPARK_IDENT_STRING=sc
  # spark-daemon.sh treats SPARK_MASTER as "rsync SPARK_HOME from here": never inherit it.
  unset SPARK_MASTER
  # JVM temp files (e.g. extracted native libs) under DIR too; driver/executors via spark-defaults.conf
  export SPARK_DAEMON_JAVA_OPTS="-Djava.io.tmpdir=$DIR/tmp"
  # The master's REST submission server would otherwise grab the fixed port 6066.
  export SPARK_MASTER_OPTS="-Dspark.master.rest.enabled=false -XX:TieredStopAtLevel=1 -XX:+UseSerialGC"
  export SPARK_WORKER_OPTS="-XX:TieredStopAtLevel=1 -XX:+UseSerialGC"
}

MASTER=org.apache.spark.deploy.master.Master
WORKER=org.apache.spark.deploy.worker.Worker
CONNECT=org.apache.spark.sql.connect.service.SparkConnectServer
pidfile() { echo "$SPARK_PID_DIR/spark-sc-$1-$2.pid"; }   # spark-daemon.sh's naming
# Pid from a pid file, only if that process is still one of ours (its classpath has DIR/conf).
pid_of() {
  local p; p=$(cat "$(pidfile "$1" "$2")" 2>/dev/null) || return 0
  if grep -qaF "$SPARK_CONF_DIR/" "/proc/$p/cmdline" 2>/dev/null; then echo "$p"; fi
}
free_port() { "$PY" -c 'import socket; s=socket.socket(); s.bind(("127.0.0.1",0)); print(s.getsockname()[1])'; }
alive() { [ -n "${1:-}" ] && kill -0 "$1" 2>/dev/null; }
# Active (non-driver) executors of the one application, from the driver's REST API (URL = argv[1]).
COUNT_EXECUTORS='
import json, sys, urllib.request
get = lambda u: json.load(urllib.request.urlopen(u, timeout=5))
app = get(sys.argv[1])[0]["id"]
print(sum(e["id"] != "driver" and e["isActive"] for e in get(f"{sys.argv[1]}/{app}/executors")))'

# Executor JVMs belonging to this DIR: their working directory is DIR/work/<app>/<n>.
executors() {
  local p
  for p in /proc/[0-9]*; do
    grep -qa CoarseGrainedExecutorBackend "$p/cmdline" 2>/dev/null || continue
    case $(readlink "$p/cwd" 2>/dev/null) in "$SPARK_WORKER_DIR"/*) echo "${p#/proc/}";; esac
  done
}

fail() {
  echo "spark_cluster: $*" >&2
  local f
  for f in "$SPARK_LOG_DIR"/*.out; do   # first errors + last lines of each log, minus stack frames
    [ -f "$f" ] || continue
    { echo "==> $f <=="; grep -E 'ERROR|Exception' "$f" | head -n 5; tail -n 8 "$f"; } \
      | grep -v $'^\t*at ' | cut -c1-400 >&2 || true
  done
  stop; exit 1
}

start() {
  local mport=${SC_MASTER_PORT:-$(free_port)} mui=${SC_MASTER_UI_PORT:-$(free_port)}
  local cport=${SC_CONNECT_PORT:-$(free_port)} cui=${SC_CONNECT_UI_PORT:-$(free_port)}
  local timeout=${SPARK_START_TIMEOUT:-180} t0=$SECONDS daemon=$SPARK_HOME/sbin/spark-daemon.sh d p
  [ -z "$(pid_of $MASTER 1)$(pid_of $WORKER 1)$(pid_of $WORKER 2)$(pid_of $CONNECT 1)" ] \
    || die "a cluster is already running in $DIR; stop it first"
  for p in "$mport" "$mui" "$cport" "$cui"; do
    ! (exec 3<>"/dev/tcp/127.0.0.1/$p") 2>/dev/null || die "port $p on 127.0.0.1 is already in use"
  done
  rm -f "$DIR/connect_url"
  mkdir -p "$SPARK_LOG_DIR" "$SPARK_PID_DIR" "$SPARK_WORKER_DIR" "$SPARK_LOCAL_DIRS" "$SPARK_CONF_DIR" "$DIR/tmp"
  cat > "$SPARK_CONF_DIR/spark-defaults.conf" <<EOF
spark.driver.host                  127.0.0.1
spark.driver.bindAddress           127.0.0.1
spark.driver.extraJavaOptions      -Djava.io.tmpdir=$DIR/tmp
spark.executor.extraJavaOptions    -Djava.io.tmpdir=$DIR/tmp
spark.executor.cores               1
spark.executor.memory              1g
spark.cores.max                    2
spark.sql.shuffle.partitions       4
spark.connect.grpc.binding.address 127.0.0.1
spark.sql.warehouse.dir            $DIR/warehouse
EOF
  cd "$DIR"   # the daemons' working dir: anything cwd-relative (derby.log, ...) lands here

  # 1. Standalone master (small heap, C1-only JIT: it does little work). Wait until it is ALIVE,
  #    since workers and the driver only retry registration every 5-20 s.
  SPARK_DAEMON_MEMORY=256m "$daemon" start $MASTER 1 --host 127.0.0.1 --port "$mport" --webui-port "$mui" >/dev/null
  until curl -sf "http://127.0.0.1:$mui/json/" 2>/dev/null | grep -q '"status" *: *"ALIVE"'; do
    (( SECONDS - t0 < timeout )) || fail "master not alive after ${timeout}s"
    alive "$(pid_of $MASTER 1)" || fail "master died"
    sleep 1
  done
  # 2. In parallel: two workers (1 core, 1g each; the executors are child JVMs of these), and the
  #    Connect server = the driver, asking for one 1-core executor per worker. The launcher treats
  #    the Connect server like the Thrift server: SPARK_DAEMON_MEMORY (not --driver-memory) is its heap.
  for i in 1 2; do
    SPARK_DAEMON_MEMORY=256m "$daemon" start $WORKER "$i" --host 127.0.0.1 --port 0 --webui-port 0 \
      --cores 1 --memory 1g --work-dir "$SPARK_WORKER_DIR" "spark://127.0.0.1:$mport" >/dev/null &
  done
  SPARK_DAEMON_MEMORY=1g "$SPARK_HOME/sbin/start-connect-server.sh" --master "spark://127.0.0.1:$mport" \
    --conf spark.connect.grpc.binding.port="$cport" --conf spark.ui.port="$cui" >/dev/null &
  wait

  # Ready = our server logged that gRPC is up, the port accepts connections, and the driver's
  # REST API lists 2 active executors.
  local n=0 log=("$SPARK_LOG_DIR"/"spark-sc-$CONNECT-1-"*.out)
  until grep -q "Spark Connect server started at" "${log[@]}" 2>/dev/null \
        && (exec 3<>"/dev/tcp/127.0.0.1/$cport") 2>/dev/null && [ "$n" -ge 2 ]; do
    (( SECONDS - t0 < timeout )) || fail "not ready after ${timeout}s (active executors: $n)"
    for d in "$MASTER 1" "$WORKER 1" "$WORKER 2" "$CONNECT 1"; do   # $d is split on purpose
      # shellcheck disable=SC2086
      alive "$(pid_of $d)" || fail "${d##*.} died"
    done
    sleep 1
    n=$("$PY" -c "$COUNT_EXECUTORS" "http://127.0.0.1:$cui/api/v1/applications" 2>/dev/null) || n=0
  done
  echo "sc://127.0.0.1:$cport" > "$DIR/connect_url"
  printf 'master=spark://127.0.0.1:%s\nmaster_ui=http://127.0.0.1:%s\nconnect_ui=http://127.0.0.1:%s\n' \
    "$mport" "$mui" "$cui" > "$DIR/ports"
  echo "Spark Connect ready at sc://127.0.0.1:$cport ($n executors, $((SECONDS - t0))s)"
}

# Stop pids: TERM, then KILL whatever is left after 20 s.
stop_pids() {
  local p i left
  [ $# -gt 0 ] || return 0
  kill "$@" 2>/dev/null || true
  for i in $(seq 40); do
    left=(); for p in "$@"; do alive "$p" && left+=("$p"); done
    [ ${#left[@]} -eq 0 ] && return 0
    sleep 0.5
  done
  kill -9 "${left[@]}" 2>/dev/null || true
  sleep 0.5
}

# shellcheck disable=SC2046  # pid lists are word-split on purpose
stop() {
  # Driver first (it releases its executors), then workers (they kill their executors) and master.
  stop_pids $(pid_of $CONNECT 1)
  stop_pids $(pid_of $WORKER 1) $(pid_of $WORKER 2) $(pid_of $MASTER 1)
  stop_pids $(executors)   # orphaned executors, if any
  rm -f "$SPARK_PID_DIR"/*.pid "$DIR/connect_url"
}

case $CMD in
  install) install ;;
  start) setup_env; start ;;
  stop) setup_env; stop ;;
  executors) setup_env; executors ;;
  *) usage ;;
esac
