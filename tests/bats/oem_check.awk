# An OEM checker independent of the C++ writer (POSIX awk; mawk and gawk):
#
#   awk -v epoch0=MJD2000 -f oem_check.awk trajectory.csv trajectory.oem
#
# Reads trajectory.csv, then parses trajectory.oem by the strict KVN grammar of a CCSDS OEM 2.0
# (502.0-B-3): the first line CCSDS_OEM_VERS = 2.0; a header of COMMENT lines, then CREATION_DATE
# and ORIGINATOR; one or more segments, each META_START, COMMENT lines, KEY = value lines of the
# metadata keywords (each once, the required ones present), META_STOP, then COMMENT lines and data
# lines of exactly 7 fields (epoch, x, y, z [km], vx, vy, vz [km/s]); blank lines anywhere; nothing
# else. Within a segment the epochs increase strictly, the first is START_TIME and the last
# STOP_TIME; segments do not go back in time. Every data line, in order, must be the CSV's row of
# the same index: its epoch within 1 microsecond of epoch0 + t_days (TDB), every component within
# 1e-9 relative. Prints "segments N data_lines M" on success; else one line per error on stderr,
# exit 1.

function fail(msg) {
  printf "oem_check: %s:%d: %s\n", FILENAME, FNR, msg > "/dev/stderr"
  errors++
}

function absval(x) { return x < 0 ? -x : x }

# Days from 2000-01-01 to the civil date y-m-d (H. Hinnant's days_from_civil).
function days_from_civil(y, m, d,    era, yoe, doy, doe) {
  y -= (m <= 2)
  era = int((y >= 0 ? y : y - 399) / 400)
  yoe = y - era * 400
  doy = int((153 * (m + (m > 2 ? -3 : 9)) + 2) / 5) + d - 1
  doe = yoe * 365 + int(yoe / 4) - int(yoe / 100) + doy
  return era * 146097 + doe - 730425
}

# Seconds of TDB since 2000-01-01T00:00:00 (MJD2000 0) of an epoch YYYY-MM-DDThh:mm:ss[.f...], or "" if malformed.
function epoch_seconds(s,    y, mo, d, h, mi, sec) {
  if (s !~ /^[0-9][0-9][0-9][0-9]-[0-9][0-9]-[0-9][0-9]T[0-9][0-9]:[0-9][0-9]:[0-9][0-9](\.[0-9]+)?$/) return ""
  y = substr(s, 1, 4) + 0; mo = substr(s, 6, 2) + 0; d = substr(s, 9, 2) + 0
  h = substr(s, 12, 2) + 0; mi = substr(s, 15, 2) + 0; sec = substr(s, 18) + 0
  if (mo < 1 || mo > 12 || d < 1 || d > 31 || h > 23 || mi > 59 || sec >= 60) return ""
  return days_from_civil(y, mo, d) * 86400 + h * 3600 + mi * 60 + sec
}

function is_number(s) { return s ~ /^[+-]?([0-9]+\.?[0-9]*|\.[0-9]+)([eE][+-]?[0-9]+)?$/ }

function end_segment() {
  if (section == "data" || section == "data_comments") {
    if (seg_lines == 0) fail("segment " segments " has no data line")
    else if (last_epoch != meta["STOP_TIME"]) fail("STOP_TIME " meta["STOP_TIME"] " is not the last epoch " last_epoch)
  }
}

BEGIN {
  if (epoch0 == "") epoch0 = 0.5  # J2000.0, the default epoch of a problem without one
  allowed_meta = " OBJECT_NAME OBJECT_ID CENTER_NAME REF_FRAME REF_FRAME_EPOCH TIME_SYSTEM START_TIME USEABLE_START_TIME USEABLE_STOP_TIME STOP_TIME INTERPOLATION INTERPOLATION_DEGREE "
  required_meta = "OBJECT_NAME OBJECT_ID CENTER_NAME REF_FRAME TIME_SYSTEM START_TIME STOP_TIME"
  section = "start"
}

# ---- trajectory.csv --------------------------------------------------------------------------
FILENAME == ARGV[1] {
  if (FNR == 1) {
    n = split($0, head, ",")
    for (i = 1; i <= n; i++) col[head[i]] = i
    split("t_days rx_km ry_km rz_km vx_km_s vy_km_s vz_km_s", want, " ")
    for (i = 1; i <= 7; i++) {
      if (!(want[i] in col)) { fail("no column " want[i]); exit 1 }
      wcol[i] = col[want[i]]
    }
    next
  }
  if ($0 == "") next
  split($0, f, ",")
  rows++
  for (i = 1; i <= 7; i++) csv[rows, i] = f[wcol[i]] + 0
  next
}

# ---- trajectory.oem --------------------------------------------------------------------------
{ sub(/\r$/, "") }
/^[ \t]*$/ { next }

section == "start" {
  if ($0 !~ /^CCSDS_OEM_VERS[ \t]*=[ \t]*2\.0[ \t]*$/) fail("the first line is not CCSDS_OEM_VERS = 2.0")
  section = "header"; next
}

/^COMMENT( |$)/ {
  if (section == "header" && (header_seen["CREATION_DATE"] || header_seen["ORIGINATOR"])) fail("COMMENT after the header's keywords")
  else if (section == "meta" && meta_keys > 0) fail("COMMENT inside the metadata after its keywords")
  else if (section == "data") fail("COMMENT between data lines")
  next
}

/^META_START[ \t]*$/ {
  if (section == "header") {
    if (!header_seen["CREATION_DATE"] || !header_seen["ORIGINATOR"]) fail("the header lacks CREATION_DATE or ORIGINATOR")
  } else if (section == "meta") fail("META_START inside a metadata block")
  else end_segment()
  section = "meta"; segments++; meta_keys = 0; seg_lines = 0; split("", meta); next
}

/^META_STOP[ \t]*$/ {
  if (section != "meta") { fail("META_STOP outside a metadata block"); next }
  n = split(required_meta, req, " ")
  for (i = 1; i <= n; i++) if (!(req[i] in meta)) fail("segment " segments " lacks " req[i])
  if (meta["TIME_SYSTEM"] != "TDB") fail("TIME_SYSTEM is not TDB")
  if (epoch_seconds(meta["START_TIME"]) == "" || epoch_seconds(meta["STOP_TIME"]) == "") fail("a malformed START_TIME or STOP_TIME")
  section = "data_comments"; next
}

/^[A-Z][A-Z0-9_]*[ \t]*=/ {
  key = $0; sub(/[ \t]*=.*/, "", key)
  value = $0; sub(/^[^=]*=[ \t]*/, "", value); sub(/[ \t]+$/, "", value)
  if (value == "") { fail(key " has no value"); next }
  if (section == "header") {
    if (key != "CREATION_DATE" && key != "ORIGINATOR") fail(key " is not a header keyword")
    else if (header_seen[key]++) fail(key " given twice")
    else if (key == "ORIGINATOR" && !header_seen["CREATION_DATE"]) fail("ORIGINATOR before CREATION_DATE")
    else if (key == "CREATION_DATE" && epoch_seconds(value) == "") fail("CREATION_DATE " value " is not an epoch")
  } else if (section == "meta") {
    if (index(allowed_meta, " " key " ") == 0) fail(key " is not a metadata keyword")
    else if (key in meta) fail(key " given twice in segment " segments)
    meta[key] = value; meta_keys++
  } else fail("KEY = value line in the data section: " key)
  next
}

section == "data_comments" || section == "data" {
  section = "data"
  if (NF != 7) { fail("a data line of " NF " fields, not 7"); next }
  t = epoch_seconds($1)
  if (t == "") { fail("malformed epoch " $1); next }
  for (i = 2; i <= 7; i++) if (!is_number($i)) { fail("field " i " '" $i "' is not a number"); next }
  if (seg_lines == 0) {
    if ($1 != meta["START_TIME"]) fail("the first epoch " $1 " is not START_TIME " meta["START_TIME"])
    if (segments > 1 && t < last_t) fail("segment " segments " starts before the previous one ends")
  } else if (t <= last_t) fail("epoch " $1 " does not increase within segment " segments)
  seg_lines++; lines++; last_t = t; last_epoch = $1
  if (lines > rows) { fail("more data lines than trajectory.csv has rows (" rows ")"); next }
  if (absval(t - (epoch0 + csv[lines, 1]) * 86400) > 1e-6)
    fail(sprintf("epoch %s is not t_days %.15g of CSV row %d", $1, csv[lines, 1], lines))
  for (i = 2; i <= 7; i++) {
    a = $i + 0; b = csv[lines, i]
    if (absval(a - b) > 1e-9 * (absval(a) > absval(b) ? absval(a) : absval(b)))
      fail(sprintf("component %d: %.17g is not CSV row %d's %.17g", i - 1, a, lines, b))
  }
  next
}

{ fail("not a line of the OEM grammar: " substr($0, 1, 60)) }

END {
  if (section == "meta") fail("the file ends inside a metadata block")
  end_segment()
  if (segments == 0) fail("no segment")
  if (lines != rows) { printf "oem_check: %d data lines, trajectory.csv has %d rows\n", lines, rows > "/dev/stderr"; errors++ }
  if (errors) exit 1
  printf "segments %d data_lines %d\n", segments, lines
}
