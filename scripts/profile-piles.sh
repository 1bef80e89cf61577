#!/usr/bin/env bash
# Where a physics step's time goes in the scaling benchmark's both-hands piles of 10 and 50
# cubes: callgrind's inclusive instruction counts of the step's parts, as shares of the whole
# step (Simulation::step_sampling). Prints a Markdown table; scripts/benchmark.sh puts it in
# BENCHMARKS.md. Usage: profile-piles.sh BUILD_DIR
set -euo pipefail
build=$1
if ! command -v valgrind >/dev/null || ! command -v callgrind_annotate >/dev/null; then
    sudo=()
    [ "$(id -u)" -ne 0 ] && sudo=(sudo)
    "${sudo[@]}" apt-get update
    DEBIAN_FRONTEND=noninteractive "${sudo[@]}" apt-get install -y --no-install-recommends valgrind
fi
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
counts=(10 50)
for n in "${counts[@]}"; do
    valgrind --tool=callgrind --callgrind-out-file="$work/$n.out" \
        "$build/tests/physhand-scaling" --profile-pile "$n" 2>/dev/null
    # Function totals only: the lines that name the object file the function is in.
    callgrind_annotate --inclusive=yes --threshold=100 "$work/$n.out" |
        sed -n 's/^ *\([0-9,]*\) ([ 0-9.]*%) *[^ :]*:\([^[]*\) \[.*\]$/\1\t\2/p' |
        tr -d ',' >"$work/$n.tsv"
done
# label <TAB> function-name prefixes, space-separated (summed)
rows='the whole step	physhand::Simulation::step_sampling(
Bullet solver: setup (contact rows)	btSequentialImpulseConstraintSolver::solveGroupCacheFriendlySetup(
Bullet solver: iterations	btSequentialImpulseConstraintSolver::solveGroupCacheFriendlyIterations(
narrowphase, every pair	btCollisionDispatcher::dispatchAllCollisionPairs(
… of it capsule–box (physhand)	physhand::(anonymous namespace)::CapsuleBoxAlgorithm::processCollision(
… of it box–box (Bullet)	btBoxBoxCollisionAlgorithm::processCollision(
hand point contacts (physhand)	physhand::add_hand_point_contacts(
broadphase and bounding boxes	btCollisionWorld::updateAabbs( btDbvtBroadphase::calculateOverlappingPairs(
islands and sleeping	btSimulationIslandManager::buildIslands( btSimulationIslandManager::updateActivationState(
integration and prediction	btDiscreteDynamicsWorld::integrateTransforms( btDiscreteDynamicsWorld::predictUnconstraintMotion( btDiscreteDynamicsWorld::createPredictiveContacts(
drives (physhand)	physhand::PhysicalHand::drive(
speed limits (physhand)	physhand::limit_speeds(
contact bookkeeping (physhand)	physhand::Simulation::collect_contacts(
reading the hands back (physhand)	physhand::Simulation::publish_hand(
gating, filters, tracking gaps (physhand)	physhand::Simulation::update_hand_gate(
allocation (malloc, free, new, delete)	malloc( free( operator new( operator delete('
header="| part of the step |"
rule="|---|"
for n in "${counts[@]}"; do
    header+=" $n cubes |"
    rule+="---|"
done
echo "$header"
echo "$rule"
while IFS=$'\t' read -r label prefixes; do
    line="| $label |"
    for n in "${counts[@]}"; do
        line+=$(awk -F'\t' -v prefixes="$prefixes" '
            BEGIN { k = split(prefixes, p, " ") }
            $2 ~ /^physhand::Simulation::step_sampling\(/ && $1 > total { total = $1 }
            { for (i = 1; i <= k; ++i) if (index($2, p[i]) == 1 && $1 > best[i]) best[i] = $1 }
            END { for (i = 1; i <= k; ++i) sum += best[i]; printf " %.1f %% |", 100 * sum / total }
        ' "$work/$n.tsv")
    done
    echo "$line"
done <<<"$rows"
