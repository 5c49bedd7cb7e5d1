#!/bin/bash
# Runs docs/slurm/hybrid-sweep.sbatch on a throw-away one-node Slurm cluster on this machine and
# checks what it does: a tiny sweep in 3 shards, merged, equals one direct run of the same flags
# in every non-timing value; a failed shard blocks the merge until it is rerun alone; merging
# again is harmless; arrays from 0, with a stride or beyond SHARDS, and requests no node can
# hold, are handled as the file says. Prints PASS/FAIL per check; exits 1 if any failed.
#
#   sudo apt-get install -y slurm-wlm        # Debian 12: Slurm 22.05 and munge
#   RENDERLAB=target/release/renderlab bash scripts/slurm_check.sh
#
# Needs root (the daemons run as root), the slurm-wlm and munge binaries, python3 and a
# renderlab binary (RENDERLAB; default target/release/renderlab, else `renderlab` on PATH).
# Everything (munge key, slurm.conf, state, logs, the runs) lives in a new directory under
# /tmp (WORK, kept at the end and printed); munged, slurmctld and slurmd are started from their
# binaries in the foreground, remembered by PID and stopped by PID at exit. The ports are
# SLURMCTLD_PORT and SLURMD_PORT (6817, 6818): nothing else may listen there.
set -euo pipefail

REPO=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
SBATCH_FILE=$REPO/docs/slurm/hybrid-sweep.sbatch
if [ -z "${RENDERLAB:-}" ]; then
    if [ -x "$REPO/target/release/renderlab" ]; then RENDERLAB=$REPO/target/release/renderlab
    else RENDERLAB=$(command -v renderlab || true); fi
fi
[ -n "$RENDERLAB" ] && [ -x "$RENDERLAB" ] || { echo "slurm_check: set RENDERLAB to a renderlab binary" >&2; exit 2; }
RENDERLAB=$(cd "$(dirname "$RENDERLAB")" && pwd)/$(basename "$RENDERLAB")
FILES_ONLY=0
if [ "${1:-}" = --files-only ]; then FILES_ONLY=1; fi
NEEDED=(python3)
if [ "$FILES_ONLY" = 0 ]; then NEEDED+=(munged slurmctld slurmd sbatch squeue sinfo scontrol scancel flock); fi
for b in "${NEEDED[@]}"; do
    command -v "$b" >/dev/null || { echo "slurm_check: $b not found (apt-get install slurm-wlm)" >&2; exit 2; }
done
if [ "$FILES_ONLY" = 0 ] && [ "$(id -u)" != 0 ]; then
    echo "slurm_check: run as root (the daemons run as root), or with --files-only" >&2
    exit 2
fi

WORK=$(mktemp -d /tmp/slurm-check.XXXXXX)
chmod 700 "$WORK"
# A copy, so that a rebuild of the binary during the check cannot mix two versions.
cp "$RENDERLAB" "$WORK/renderlab"
RENDERLAB=$WORK/renderlab
HOST=$(hostname -s)
CTLD_PORT=${SLURMCTLD_PORT:-6817}
SLURMD_PORT=${SLURMD_PORT:-6818}
PIDS=()
FAILS=0

pass() { echo "PASS  $*"; }
fail() {
    echo "FAIL  $*"
    FAILS=$((FAILS + 1))
}
note() { echo "NOTE  $*"; }

stop_daemons() {
    local p
    if [ "${#PIDS[@]}" -gt 0 ]; then
        squeue -h -o %A 2>/dev/null | while read -r j; do scancel "$j" 2>/dev/null || true; done
        # slurmd, slurmctld, munged: the reverse of their start.
        for ((i = ${#PIDS[@]} - 1; i >= 0; i--)); do
            p=${PIDS[i]}
            kill "$p" 2>/dev/null || true
            for _ in $(seq 50); do kill -0 "$p" 2>/dev/null || break; sleep 0.1; done
            kill -0 "$p" 2>/dev/null && kill -9 "$p" 2>/dev/null || true
            echo "stopped PID $p"
        done
        PIDS=()
    fi
}
# The copy of the binary goes at exit; the rest of WORK stays for a look.
trap 'stop_daemons; rm -f "$WORK/renderlab"' EXIT

# --- helpers ---------------------------------------------------------------------------------
cd "$WORK"

# Waits until job $1 (every task of it) has left the queue.
wait_job() {
    for _ in $(seq 300); do
        [ -z "$(squeue -h -j "$1" 2>/dev/null)" ] && return 0
        sleep 1
    done
    echo "job $1 still queued after 300 s:"
    squeue -j "$1"
    return 1
}

# The state of every task of job $1, as "TASK:STATE", sorted.
job_states() {
    scontrol -o show job "$1" | sed -n 's/.*ArrayTaskId=\([0-9]*\) .*JobState=\([A-Z_]*\) .*/\1:\2/p' | sort -n | tr '\n' ' '
}

# Submits through the file with bash (the submit-time check, then sbatch); prints the job id.
submit() {
    local out
    out=$(env "$@" bash "$SBATCH_FILE" 2>&1) || { echo "$out" >&2; return 1; }
    echo "$out" | sed -n 's/^Submitted batch job \([0-9]*\)$/\1/p'
}

# results.json of two run directories equal in every value but the timings, results.csv in every
# column but the timings, the references' records likewise, and the images byte for byte.
same_results() {
    python3 - "$1" "$2" <<'EOF'
import csv, hashlib, json, os, sys
TIMING = {"frame_ms", "frame_min_ms", "frame_max_ms", "stage_ms", "baseline_ms", "delta_ms",
          "delta_ratio", "seconds"}
def strip(v):
    if isinstance(v, dict):
        return {k: strip(x) for k, x in v.items() if k not in TIMING}
    if isinstance(v, list):
        return [strip(x) for x in v]
    return v
a, b = sys.argv[1], sys.argv[2]
ja, jb = (strip(json.load(open(os.path.join(d, "results.json")))) for d in (a, b))
if ja != jb:
    sys.exit("results.json differ beyond the timings")
def rows(d):
    with open(os.path.join(d, "results.csv")) as f:
        return [{k: v for k, v in r.items() if k not in TIMING} for r in csv.DictReader(f)]
ra, rb = rows(a), rows(b)
if ra != rb:
    sys.exit("results.csv differ beyond the timings")
def files(d):
    out = {}
    for sub in ("img", "refs"):
        for root, _, names in os.walk(os.path.join(d, sub)):
            for n in names:
                p = os.path.join(root, n)
                if n.endswith(".json"):  # a reference's record: its time is a timing
                    out[os.path.relpath(p, d)] = strip(json.load(open(p)))
                else:
                    out[os.path.relpath(p, d)] = hashlib.sha256(open(p, "rb").read()).hexdigest()
    return out
fa, fb = files(a), files(b)
if fa != fb:
    diff = sorted(set(fa) ^ set(fb)) or sorted(k for k in fa if fa[k] != fb[k])
    sys.exit(f"images or references differ: {diff[:5]}")
n = len(ja["records"])
imgs = sum(1 for k in fa if not k.endswith(".json"))
print(f"{n} records and {len(ra[0]) if ra else 0} non-timing CSV columns equal, {imgs} images byte-identical")
EOF
}

# The tiny sweep.
SWEEP_ENV=(SCENES=showcase RESOLUTION=64x36 REFERENCE_SPP=4 SWEEP=report REPS=1 WARMUP=0 SEED=1
    SHARDS=3 CPUS=1 MEM=1G TIME_LIMIT=00:10:00)
"$RENDERLAB" hybrid bench --scenes showcase --resolution 64x36 --reference-spp 4 --sweep report \
    --reps 1 --warmup 0 --seed 1 --out "$WORK/direct" >"$WORK/direct.out" 2>&1
echo "direct run: $RENDERLAB hybrid bench --scenes showcase --resolution 64x36 --reference-spp 4 --sweep report --reps 1 --warmup 0 --seed 1"

# A renderlab whose first run of shard 2 crashes after rendering its rows, before its
# results.json, with one row lost (as a task killed mid-run leaves its part). It renders into
# a private directory and moves the damaged part into place, so that no other task ever sees
# shard 2 finished.
cat >"$WORK/renderlab-flaky" <<EOF
#!/bin/bash
args=("\$@"); out=""; shard=""
for ((i = 0; i < \${#args[@]}; i++)); do
    case "\${args[i]}" in
        --out) out=\${args[i+1]}; args[i+1]=\$out.crash ;;
        --shard) shard=\${args[i+1]} ;;
    esac
done
if [ "\$1" = hybrid ] && [ "\${shard%/*}" = 2 ] && [ ! -e "$WORK/flaky.done" ]; then
    touch "$WORK/flaky.done"
    "$RENDERLAB" "\${args[@]}" || exit
    rm -f "\$out.crash"/results.json "\$out.crash"/results.csv "\$out.crash"/index.html
    rm -f "\$(ls "\$out.crash"/rows/*.json | head -1)"
    rm -rf "\$out" && mv "\$out.crash" "\$out"
    echo "renderlab-flaky: shard \$shard crashed (injected)" >&2
    exit 3
fi
exec "$RENDERLAB" "\$@"
EOF
chmod +x "$WORK/renderlab-flaky"

# --- the files themselves ----------------------------------------------------------------------
# The sbatch file's #SBATCH request equals its CPUS/MEM/TIME_LIMIT defaults; the Kubernetes file
# parses, and its ConfigMap holds the sbatch file's run variables with the same defaults, its
# completions equal SHARDS, its request equals CPUS/MEM, and with the GPU line uncommented it
# asks for one GPU.
files_check() {
    python3 - "$SBATCH_FILE" "$REPO/docs/k8s/hybrid-sweep.yaml" <<'EOF'
import re, sys
sb, k8s = open(sys.argv[1]).read(), open(sys.argv[2]).read()
var = dict(re.findall(r'^([A-Z_]+)=\$\{\1:-([^}]*)\}', sb, re.M))
run = ["SHARDS", "SCENES", "CAMERAS", "RESOLUTION", "REFERENCE_SPP", "SWEEP", "REPS", "WARMUP",
       "SEED", "NO_IMAGES", "BACKEND"]
err = []
for flag, name in (("cpus-per-task", "CPUS"), ("mem", "MEM"), ("time", "TIME_LIMIT")):
    m = re.search(rf'^#SBATCH --{flag}=(\S+)', sb, re.M)
    if not m or m.group(1) != var.get(name):
        err.append(f"#SBATCH --{flag} is {m and m.group(1)}, {name} defaults to {var.get(name)}")
try:
    import yaml
except ImportError:
    print("python3 has no yaml module: the Kubernetes file was not parsed")
    sys.exit(0 if not err else 1)
def jobs(text):
    docs = [d for d in yaml.safe_load_all(text) if d]
    kinds = [d["kind"] for d in docs]
    if kinds != ["ConfigMap", "PersistentVolumeClaim", "Job", "Job"]:
        err.append(f"documents {kinds}")
    return docs
cm, pvc, sweep, merge = jobs(k8s)
data = cm["data"]
if sorted(data) != sorted(run):
    err.append(f"ConfigMap keys {sorted(data)} != sbatch run variables {sorted(run)}")
for k in run:
    if data.get(k) != var.get(k):
        err.append(f"{k}: ConfigMap {data.get(k)!r}, sbatch {var.get(k)!r}")
s = sweep["spec"]
if s.get("completionMode") != "Indexed" or s["completions"] != int(data["SHARDS"]) or s["parallelism"] != s["completions"]:
    err.append(f"sweep Job: completions {s['completions']}, parallelism {s['parallelism']}, SHARDS {data['SHARDS']}")
shard = s["template"]["spec"]["containers"][0]
req = shard["resources"]["requests"]
if str(req["cpu"]) != var["CPUS"] or req["memory"] != var["MEM"].replace("G", "Gi"):
    err.append(f"shard request {req} != CPUS {var['CPUS']}, MEM {var['MEM']}")
if "nvidia.com/gpu" in shard["resources"].get("limits", {}):
    err.append("the default (CPU) file asks for a GPU")
for job in (sweep, merge):
    pod = job["spec"]["template"]["spec"]
    for c in pod.get("initContainers", []) + pod["containers"]:
        if c.get("envFrom") != [{"configMapRef": {"name": cm["metadata"]["name"]}}]:
            err.append(f"{job['metadata']['name']}/{c['name']} does not take the ConfigMap")
    if pod["volumes"][0]["persistentVolumeClaim"]["claimName"] != pvc["metadata"]["name"]:
        err.append(f"{job['metadata']['name']} mounts another claim")
gpu_text = k8s.replace("# nvidia.com/gpu: 1", "nvidia.com/gpu: 1")
g = jobs(gpu_text)[2]["spec"]["template"]["spec"]["containers"][0]["resources"]["limits"]
if g.get("nvidia.com/gpu") != 1:
    err.append(f"GPU variant limits {g}")
if err:
    print("; ".join(err))
    sys.exit(1)
print(f"4 documents; ConfigMap = the sbatch file's {len(run)} run variables and defaults; "
      f"completions = SHARDS = {data['SHARDS']}; request {req['cpu']} CPUs, {req['memory']} = CPUS, MEM; "
      "GPU line uncommented: nvidia.com/gpu 1; #SBATCH request = CPUS/MEM/TIME_LIMIT defaults")
EOF
}
out=$(files_check 2>&1) && rc=0 || rc=$?
if [ "$rc" = 0 ]; then pass "files: $out"; else fail "files: $out"; fi

# The Kubernetes file's pod scripts, run here under /bin/sh with /results in a directory:
# three shard pods, one pod beyond SHARDS, the init container and the merge twice.
K8S=$WORK/k8s
mkdir -p "$K8S/results" "$K8S/bin"
ln -s "$RENDERLAB" "$K8S/bin/renderlab"
python3 - "$REPO/docs/k8s/hybrid-sweep.yaml" "$K8S" <<'EOF'
import re, sys
try:
    import yaml
except ImportError:
    sys.exit(0)
docs = [d for d in yaml.safe_load_all(open(sys.argv[1])) if d]
def pod(i):
    return docs[i]["spec"]["template"]["spec"]
for name, text in (("shard", pod(2)["containers"][0]["args"][0]),
                   ("wait", pod(3)["initContainers"][0]["args"][0]),
                   ("merge", pod(3)["containers"][0]["args"][0])):
    # The mount point /results (not a results.json under it) moved into the directory.
    text = re.sub(r'(?<![\w$}])/results\b', sys.argv[2] + "/results", text)
    open(f"{sys.argv[2]}/{name}.sh", "w").write(text)
EOF
if [ -e "$K8S/shard.sh" ]; then
    K8S_ENV=(PATH="$K8S/bin:$PATH" SHARDS=3 SCENES=showcase CAMERAS= RESOLUTION=64x36 REFERENCE_SPP=4
        SWEEP=report REPS=1 WARMUP=0 SEED=1 NO_IMAGES=0 BACKEND= RAYON_NUM_THREADS=1 HOSTNAME=check)
    ok=1
    for i in 0 1 2; do
        env "${K8S_ENV[@]}" JOB_COMPLETION_INDEX=$i sh "$K8S/shard.sh" >"$K8S/shard-$i.out" 2>&1 || ok=0
    done
    env "${K8S_ENV[@]}" JOB_COMPLETION_INDEX=3 sh "$K8S/shard.sh" >"$K8S/shard-3.out" 2>&1 && ok=0
    grep -q "beyond SHARDS=3" "$K8S/shard-3.out" || ok=0
    env "${K8S_ENV[@]}" BACKEND=gpu JOB_COMPLETION_INDEX=0 sh "$K8S/shard.sh" >"$K8S/shard-gpu.out" 2>&1 && ok=0
    env "${K8S_ENV[@]}" timeout 10 sh "$K8S/wait.sh" >"$K8S/wait.out" 2>&1 || ok=0
    env "${K8S_ENV[@]}" sh "$K8S/merge.sh" >"$K8S/merge-1.out" 2>&1 || ok=0
    env "${K8S_ENV[@]}" sh "$K8S/merge.sh" >"$K8S/merge-2.out" 2>&1 || ok=0
    if [ "$ok" = 1 ] && res=$(same_results "$WORK/direct" "$K8S/results/merged" 2>&1) &&
        [ -z "$(ls -A "$K8S/results" | grep -E '^\.merged\.' || true)" ]; then
        pass "Kubernetes pod scripts under sh: 3 shard pods, merged twice = direct run: $res; index 3 and BACKEND=gpu without a GPU refused: $(head -1 "$K8S/shard-gpu.out")"
    else
        fail "Kubernetes pod scripts (outputs in $K8S): ${res:-}"
    fi
else
    note "python3 has no yaml module: the Kubernetes pod scripts were not run"
fi
if [ "$FILES_ONLY" = 1 ]; then
    if [ "$FAILS" = 0 ]; then echo "slurm_check: all checks passed ($WORK)"; else echo "slurm_check: $FAILS checks failed ($WORK)"; fi
    exit $((FAILS > 0))
fi

# --- the cluster -----------------------------------------------------------------------------
dd if=/dev/urandom of="$WORK/munge.key" bs=1024 count=1 status=none
chmod 400 "$WORK/munge.key"
munged --foreground --force --key-file="$WORK/munge.key" --socket="$WORK/munge.sock" \
    --pid-file="$WORK/munged.pid" --log-file="$WORK/munged.log" --seed-file="$WORK/munged.seed" \
    >"$WORK/munged.out" 2>&1 &
PIDS+=($!)
for _ in $(seq 50); do [ -S "$WORK/munge.sock" ] && break; sleep 0.1; done
[ -S "$WORK/munge.sock" ] || { echo "munged did not start:"; cat "$WORK/munged.out" "$WORK/munged.log"; exit 1; }

NODE=$(slurmd -C | head -1) # NodeName=HOST CPUs=... RealMemory=...
mkdir -p "$WORK/state" "$WORK/spool"
cat >"$WORK/slurm.conf" <<EOF
ClusterName=slurmcheck
SlurmctldHost=$HOST
SlurmctldPort=$CTLD_PORT
SlurmdPort=$SLURMD_PORT
SlurmUser=root
SlurmdUser=root
AuthType=auth/munge
AuthInfo=socket=$WORK/munge.sock
CredType=cred/munge
StateSaveLocation=$WORK/state
SlurmdSpoolDir=$WORK/spool
SlurmctldPidFile=$WORK/slurmctld.pid
SlurmdPidFile=$WORK/slurmd.pid
SlurmctldLogFile=$WORK/slurmctld.log
SlurmdLogFile=$WORK/slurmd.log
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
JobAcctGatherType=jobacct_gather/none
AccountingStorageType=accounting_storage/none
SchedulerType=sched/backfill
SelectType=select/cons_tres
SelectTypeParameters=CR_Core_Memory
ReturnToService=2
MinJobAge=3600
$NODE State=UNKNOWN
PartitionName=check Nodes=$HOST Default=YES MaxTime=INFINITE State=UP
EOF
export SLURM_CONF=$WORK/slurm.conf
slurmctld -D -f "$SLURM_CONF" >"$WORK/slurmctld.out" 2>&1 &
PIDS+=($!)
sleep 2
slurmd -D -f "$SLURM_CONF" >"$WORK/slurmd.out" 2>&1 &
PIDS+=($!)
echo "work directory $WORK; munged, slurmctld, slurmd: PIDs ${PIDS[*]}; $(sbatch --version)"
echo "node: $NODE"
for _ in $(seq 60); do
    [ "$(sinfo -h -N -o %T 2>/dev/null)" = idle ] && break
    sleep 1
done
[ "$(sinfo -h -N -o %T)" = idle ] || { echo "the node did not come up:"; tail "$WORK"/slurm*.log; exit 1; }

# --- what Slurm 22.05 does with a request no node can hold (observed, not judged) ------------
for req in "--cpus-per-task=16" "--mem=64G" "--gres=gpu:1" "--cpus-per-task=16 --immediate=5"; do
    # shellcheck disable=SC2086
    out=$(sbatch $req --wrap=true -o /dev/null 2>&1) && rc=0 || rc=$?
    j=$(echo "$out" | sed -n 's/^Submitted batch job \([0-9]*\)$/\1/p')
    if [ -n "$j" ]; then
        sleep 3
        st=$(squeue -h -j "$j" -o '%T %r')
        scancel "$j"
        note "raw sbatch $req: accepted (job $j), after 3 s: ${st:-left the queue}"
    else
        note "raw sbatch $req: exit $rc: $(echo "$out" | tr '\n' ' ')"
    fi
done

# --- the file's submit-time check ------------------------------------------------------------
for bad in "CPUS=16" "MEM=64G" "BACKEND=gpu"; do
    out=$(env "${SWEEP_ENV[@]}" RUN_DIR="$WORK/refused" $bad bash "$SBATCH_FILE" 2>&1) && rc=0 || rc=$?
    if [ "$rc" != 0 ] && [[ $out == *"no node can hold"* ]] && [ -z "$(squeue -h)" ]; then
        pass "submit with $bad refused before sbatch: $(echo "$out" | head -1)"
    else
        fail "submit with $bad: exit $rc: $out"
    fi
done

# --- the sweep: 3 shards, shard 2 crashes -----------------------------------------------------
RUN=$WORK/run
j=$(submit "${SWEEP_ENV[@]}" RUN_DIR="$RUN" RENDERLAB="$WORK/renderlab-flaky")
wait_job "$j"
st=$(job_states "$j")
if [[ $st == "1:COMPLETED 2:FAILED 3:COMPLETED "* ]] && [ ! -e "$RUN/merged" ] &&
    [ -e "$RUN/part-1/results.json" ] && [ -e "$RUN/part-3/results.json" ]; then
    pass "3-shard array (job $j: $st): shard 2 failed (injected), no merge"
else
    fail "3-shard array (job $j: $st), merged present: $([ -e "$RUN/merged" ] && echo yes || echo no)"
fi

# Shard 2 alone: it resumes (one row was lost) and, finishing the last shard, merges.
j=$(submit "${SWEEP_ENV[@]}" RUN_DIR="$RUN" RENDERLAB="$RENDERLAB" ARRAY=2)
wait_job "$j"
st=$(job_states "$j")
rendered=$(grep -E '^\[[0-9]+/[0-9]+\] showcase__0_cam1: ' hybrid-sweep-"$j"_2.out | grep -vc ': reference' || true)
if grep -q "shard 2/3" hybrid-sweep-"$j"_2.out && [ "$rendered" = 1 ] && [ -e "$RUN/merged/results.json" ] &&
    res=$(same_results "$WORK/direct" "$RUN/merged" 2>&1); then
    pass "ARRAY=2 resubmitted (job $j: $st) ran shard 2/3 (rendered the 1 lost row) and merged; merged = direct run: $res"
else
    fail "ARRAY=2 resubmitted (job $j: $st, rows rendered: $rendered): ${res:-no merge}"
fi

# Again: merges again over the earlier merge; the result is the same.
before=$(stat -c %Y "$RUN/merged/results.json")
sleep 1
j=$(submit "${SWEEP_ENV[@]}" RUN_DIR="$RUN" RENDERLAB="$RENDERLAB" ARRAY=2)
wait_job "$j"
st=$(job_states "$j")
if [ "$(stat -c %Y "$RUN/merged/results.json")" != "$before" ] &&
    res=$(same_results "$WORK/direct" "$RUN/merged" 2>&1); then
    pass "ARRAY=2 once more (job $j: $st) merged again; merged = direct run: $res"
else
    fail "ARRAY=2 once more (job $j: $st): ${res:-merged not rewritten}"
fi

# `merge` by hand, twice.
if env "${SWEEP_ENV[@]}" RUN_DIR="$RUN" RENDERLAB="$RENDERLAB" bash "$SBATCH_FILE" merge >merge1.out 2>&1 &&
    env "${SWEEP_ENV[@]}" RUN_DIR="$RUN" RENDERLAB="$RENDERLAB" bash "$SBATCH_FILE" merge >merge2.out 2>&1 &&
    res=$(same_results "$WORK/direct" "$RUN/merged" 2>&1) &&
    [ -z "$(ls -A "$RUN" | grep -E '^\.merged\.' || true)" ]; then
    pass "'merge' run twice by hand: merged = direct run, no staging left: $res"
else
    fail "'merge' twice by hand: ${res:-} $(tail -n 2 merge1.out merge2.out)"
fi

# Other settings into the same RUN_DIR: refused before rendering.
j=$(submit "${SWEEP_ENV[@]}" RUN_DIR="$RUN" RENDERLAB="$RENDERLAB" ARRAY=2 RESOLUTION=32x18)
wait_job "$j"
st=$(job_states "$j")
if [[ $st == "2:FAILED "* ]] && grep -q "other settings" hybrid-sweep-"$j"_2.out &&
    same_results "$WORK/direct" "$RUN/merged" >/dev/null 2>&1; then
    pass "ARRAY=2 with RESOLUTION=32x18 into the same RUN_DIR refused (job $j: $st): $(grep -o 'was started with other settings' hybrid-sweep-"$j"_2.out)"
else
    fail "other settings (job $j: $st): $(cat hybrid-sweep-"$j"_2.out)"
fi

# --- numbering: from 0, a stride, beyond SHARDS ------------------------------------------------
# --array=0-2 with SHARD_BASE left at 1: every task refuses.
j=$(submit "${SWEEP_ENV[@]}" RUN_DIR="$WORK/from0-wrong" RENDERLAB="$RENDERLAB" ARRAY=0-2)
wait_job "$j"
st=$(job_states "$j")
if [ "$st" = "0:FAILED 1:FAILED 2:FAILED " ] && grep -q "do not all name shards" hybrid-sweep-"$j"_0.out &&
    [ -z "$(ls "$WORK/from0-wrong" 2>/dev/null | grep part- || true)" ]; then
    pass "ARRAY=0-2 with SHARD_BASE=1: every task refused, nothing rendered (job $j: $st)"
else
    fail "ARRAY=0-2 with SHARD_BASE=1 (job $j: $st)"
fi

# --array=1-4 with SHARDS=3: every task refuses.
j=$(submit "${SWEEP_ENV[@]}" RUN_DIR="$WORK/beyond" RENDERLAB="$RENDERLAB" ARRAY=1-4)
wait_job "$j"
st=$(job_states "$j")
if [ "$st" = "1:FAILED 2:FAILED 3:FAILED 4:FAILED " ]; then
    pass "ARRAY=1-4 with SHARDS=3: every task refused (job $j: $st)"
else
    fail "ARRAY=1-4 with SHARDS=3 (job $j: $st)"
fi

# Plain sbatch (the #SBATCH request) from 0: SHARD_BASE=0, --array=0-2.
out=$(env "${SWEEP_ENV[@]}" RUN_DIR="$WORK/from0" RENDERLAB="$RENDERLAB" SHARD_BASE=0 \
    sbatch --array=0-2 --cpus-per-task=1 --mem=1G "$SBATCH_FILE")
j=${out##* }
wait_job "$j"
st=$(job_states "$j")
if grep -q "task 0: shard 1/3" hybrid-sweep-"$j"_0.out && res=$(same_results "$WORK/direct" "$WORK/from0/merged" 2>&1); then
    pass "sbatch --array=0-2 with SHARD_BASE=0 (job $j: $st): shards 1..3, merged = direct run: $res"
else
    fail "sbatch --array=0-2 with SHARD_BASE=0 (job $j: $st): ${res:-}"
fi

# A stride: --array=1-3:2 runs shards 1 and 3 and does not merge; --array=2 completes it.
j=$(submit "${SWEEP_ENV[@]}" RUN_DIR="$WORK/stride" RENDERLAB="$RENDERLAB" ARRAY=1-3:2)
wait_job "$j"
st=$(job_states "$j")
merged_early=$([ -e "$WORK/stride/merged" ] && echo yes || echo no)
j2=$(submit "${SWEEP_ENV[@]}" RUN_DIR="$WORK/stride" RENDERLAB="$RENDERLAB" ARRAY=2)
wait_job "$j2"
if [ "$st" = "1:COMPLETED 3:COMPLETED " ] && [ "$merged_early" = no ] &&
    grep -q "shards 2 of 3 have not finished" hybrid-sweep-"$j"_*.out &&
    res=$(same_results "$WORK/direct" "$WORK/stride/merged" 2>&1); then
    pass "ARRAY=1-3:2 ran shards 1 and 3 (job $j: $st) and waited for 2; ARRAY=2 (job $j2) merged = direct run: $res"
else
    fail "stride (job $j: $st, merged before shard 2: $merged_early): ${res:-}"
fi

stop_daemons
if [ "$FAILS" = 0 ]; then echo "slurm_check: all checks passed ($WORK)"; else echo "slurm_check: $FAILS checks failed ($WORK)"; fi
[ "$FAILS" = 0 ]
