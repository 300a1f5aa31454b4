# The validation campaign's definition, sourced by bench/run_validation and bench/validation_report
# (which set $repo and $me): its settings, its cases in the order they run, and the paper's values.
#
# Settings: validation/campaign.conf (VALIDATION_CONF), each entry NAME overridden by
# VALIDATION_NAME when that is set (VALIDATION_DELTA= set and empty means: calibrate).
# Paper's values: validation/paper/pullout_experiments.csv (Table 3: experiments; Table 6: the
# paper's PFC2D, already in kN/m there) and materials.csv (the sheets, Table 2): the repository's
# copies of the paper's data, so that a clone alone runs the campaign and its tests.

conf="${VALIDATION_CONF:-$repo/validation/campaign.conf}"
[[ -f "$conf" ]] || { echo "$me: the campaign's settings '$conf' do not exist" >&2; exit 1; }
# shellcheck source=/dev/null
source "$conf"
overridden=""
for name in MODE CLUSTERS SEEDS RATE DELTA CALIBRATION_START CALIBRATION_TOLERANCE SOIL; do
  variable="VALIDATION_$name"
  if [[ -n "${!variable+set}" ]]; then
    printf -v "$name" '%s' "${!variable}"
    overridden+=" $name"
  fi
done
bad_setting() { echo "$me: $1 = '${!1:-}' (in $conf or VALIDATION_$1) $2" >&2; exit 1; }
number_re='^[0-9]+([.][0-9]*)?([eE][-+]?[0-9]+)?$'
[[ "${MODE:-}" == dem || "${MODE:-}" == hybrid || "${MODE:-}" == fem ]] || bad_setting MODE "must be dem, hybrid or fem"
[[ "${CLUSTERS:-}" =~ ^[1-9][0-9]*$ ]] || bad_setting CLUSTERS "must be a positive integer"
[[ "${SEEDS:-}" =~ ^[1-9][0-9]*$ ]] || bad_setting SEEDS "must be a positive integer"
[[ "${RATE:-}" =~ $number_re ]] || bad_setting RATE "must be a positive number [m/s]"
[[ -z "${DELTA:-}" || "$DELTA" =~ $number_re ]] || bad_setting DELTA "must be an angle [deg] or empty (calibrate)"
# Older settings files have no CALIBRATION_START: the paper's angle.
CALIBRATION_START="${CALIBRATION_START:-25.6}"
[[ "$CALIBRATION_START" =~ $number_re ]] && awk -v a="$CALIBRATION_START" 'BEGIN{exit !(a > 0 && a < 90)}' || bad_setting CALIBRATION_START "must be an angle in (0, 90) deg"
[[ "${CALIBRATION_TOLERANCE:-}" =~ $number_re ]] || bad_setting CALIBRATION_TOLERANCE "must be a fraction (0.02: 2 %)"
[[ -n "${SOIL:-}" ]] || bad_setting SOIL "must name the soil's fragment (examples/soil/sand1.prm)"
# The continuum has no fill to vary: one run per case.
seeds_asked="$SEEDS"
[[ "$MODE" == fem ]] && seeds_asked=1
# Every angle is written with two decimals: the hash sees the text of an entry, 25.6 is not 25.60.
angle_text() { awk -v a="$1" 'BEGIN { printf "%.2f", a }'; }

experiments="$repo/validation/paper/pullout_experiments.csv"
materials="$repo/validation/paper/materials.csv"

# The cases in the order they run (issue 23): GT230 H = 0.40 m (the calibration case first), the
# run-outs, GT230 H = 0.50 m, GT75. D2 = H - D1; L = 1 m. A layer boundary must lie at the sheet
# and at a wrap-around's upper part: 0.2 m lifts for H = 0.40 m (the bundled inputs), 0.1 m lifts
# under 0.2 m of soil for the H = 0.50 m wrap-arounds (D1 = 0.3 m), 0.25 m for the run-out.
# name | base input | geosynthetic | H | D1 | B | fill height | layers
cases=(
  "gt230_h040_b025|wrap|GT230|0.40|0.2|0.25|0.60|3"
  "gt230_h040_b050|wrap|GT230|0.40|0.2|0.5|0.60|3"
  "gt230_h040_b0125|wrap|GT230|0.40|0.2|0.125|0.60|3"
  "gt230_h040_b075|wrap|GT230|0.40|0.2|0.75|0.60|3"
  "runout_h040|runout|GT230|0.40|-|-|0.60|3"
  "runout_h050|runout|GT230|0.50|-|-|0.75|3"
  "gt230_h050_b025|wrap|GT230|0.50|0.3|0.25|0.70|7"
  "gt230_h050_b050|wrap|GT230|0.50|0.3|0.5|0.70|7"
  "gt75_h040_b025|wrap|GT75|0.40|0.2|0.25|0.60|3"
  "gt75_h040_b050|wrap|GT75|0.40|0.2|0.5|0.60|3"
  "gt75_h050_b025|wrap|GT75|0.50|0.3|0.25|0.70|7"
  "gt75_h050_b050|wrap|GT75|0.50|0.3|0.5|0.70|7"
)
# The interface angle is calibrated on this case against Table 3 (unless DELTA is given); its
# attempts are the directories calibration_<case>_delta<angle>, and runs/<case> links to the chosen one.
calibration_case="gt230_h040_b025"
calibration_start_angle="$CALIBRATION_START" # the first attempt's angle (campaign.conf)
calibration_attempts=3
# An interface stronger than the soil only moves the failure into the soil (sand 1: 38.4 deg at
# its peak): a calibration that asks for more says that the soil is too weak, not the interface.
calibration_max_angle=45

field() { echo "$1" | cut -d'|' -f"$2"; }
case_named() {
  local c
  for c in "${cases[@]}"; do [[ "$(field "$c" 1)" == "$1" ]] && { echo "$c"; return 0; }; done
  echo "$me: no case '$1' (the cases: bench/validation_campaign.sh)" >&2
  return 1
}
# The tabulated T_max [kN/m] of a wrap-around: source (table3 or table6), geosynthetic, D1, H, B.
tabulated() {
  [[ -f "$experiments" ]] || { echo "$me: the paper's values '$experiments' do not exist" >&2; exit 1; }
  awk -F, -v s="$1" -v g="$2" -v d1="$3" -v h="$4" -v b="$5" \
    '$1 == s && $2 == "sand1" && $3 == g && $4 + 0 == d1 + 0 && $5 + 0 == h + 0 && $6 + 0 == b + 0 { print $7 }' "$experiments"
}
# A sheet's property from Table 2: geosynthetic, property (tensile_stiffness_J, thickness, unit_weight).
material() {
  [[ -f "$materials" ]] || { echo "$me: the materials '$materials' do not exist" >&2; exit 1; }
  local value
  value="$(awk -F, -v g="$1" -v p="$2" '$1 == "geosynthetic" && $2 == g && $3 == p { print $4 }' "$materials")"
  [[ -n "$value" ]] || { echo "$me: no $2 of $1 in $materials" >&2; exit 1; }
  echo "$value"
}
# A flat summary.json's value of a key (numbers, or strings without their quotes); empty if none.
summary_value() {
  [[ -f "$1" ]] || return 0
  sed -n "s/^ *\"$2\": \"\{0,1\}\([^\",]*\)\"\{0,1\},\{0,1\}$/\1/p" "$1" | head -1
}
