#!/bin/bash
# Every process test owns its LCM port: two test files on one port hear each
# other when ctest runs them at once (a lockstep test once failed so). Fails
# naming the port and the files that share it.
set -euo pipefail
cd "$1"
status=0
while read -r port; do
  files=$(grep -rlE "(TestLcmUrl\(|port = )${port}\b" tests bench | sort -u)
  if [ "$(echo "$files" | wc -l)" -gt 1 ]; then
    echo "LCM port ${port} is used by more than one test file:" $files
    status=1
  fi
done < <(grep -rhoE "(TestLcmUrl\(|port = )7[0-9]{3}\b" tests bench |
  grep -oE "7[0-9]{3}" | sort -u)
exit $status
