#!/usr/bin/env bash
# A test certificate authority for a secured DDS domain (OMG DDS Security 1.1,
# builtin plugins: PKI-DH authentication, Access-Permissions, AES-GCM-GMAC):
#
#   scripts/make_test_ca.sh DIR [--domains MIN-MAX] [--days N]
#
# writes, with openssl (ECDSA on prime256v1, SHA-256):
#   DIR/identity_ca.pem       the CA certificate every participant trusts
#   DIR/permissions_ca.pem    the same CA, as the signer of governance and permissions
#   DIR/governance.p7s        signed governance: no unauthenticated participant, every
#                             topic read- and write-access controlled, data and
#                             discovery encrypted, on domains MIN..MAX (default 0-230:
#                             Cyclone DDS 0.10 refuses a governance or grant with ids above 230)
#   DIR/ROLE/cert.pem, key.pem, permissions.p7s   for ROLE in tyre terrain coupler monitor:
#                             the identity "CN=cosim-ROLE" and its signed grant; the three
#                             programs may publish and subscribe every topic, the
#                             monitor may only subscribe
#   DIR/private/ca_key.pem    the CA's key (keep it off the run's hosts)
#
# `cosim run --security DIR` (and --security DIR on each program) secures a run
# with these files; docs/reliability.md, "DDS Security". A test CA: its private
# keys are unencrypted files. For production, make the keys on each host and
# sign only their requests.
set -euo pipefail

usage() { echo "usage: $0 DIR [--domains MIN-MAX] [--days N] [--key rsa|ec]" >&2; exit 2; }
[[ $# -ge 1 ]] || usage
dir=$1; shift
domains="0-230"
days=3650
key=rsa
while [[ $# -gt 0 ]]; do
  case $1 in
    --domains) domains=${2:?}; shift 2 ;;
    --days) days=${2:?}; shift 2 ;;
    --key) key=${2:?}; shift 2 ;;
    *) usage ;;
  esac
done
[[ $key == rsa || $key == ec ]] || { echo "$0: --key '$key': rsa or ec" >&2; exit 2; }
[[ $domains =~ ^([0-9]+)-([0-9]+)$ ]] || { echo "$0: --domains '$domains': give MIN-MAX, e.g. 0-230" >&2; exit 2; }
dmin=${BASH_REMATCH[1]} dmax=${BASH_REMATCH[2]}
((dmin <= dmax && dmax <= 230)) || { echo "$0: --domains '$domains': need MIN <= MAX <= 230" >&2; exit 2; }
command -v openssl >/dev/null || { echo "$0: openssl not found (apt-get install openssl)" >&2; exit 2; }

# Keys: RSA 2048 by default (--key ec: ECDSA on prime256v1).
new_key() {
  if [[ $key == ec ]]; then openssl genpkey -algorithm EC -pkeyopt ec_paramgen_curve:prime256v1 -out "$1"
  else openssl genpkey -algorithm RSA -pkeyopt rsa_keygen_bits:2048 -out "$1"; fi
}

mkdir -p "$dir/private"
chmod 700 "$dir/private"
cd "$dir"
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT

# The CA: self-signed, CA:TRUE (OpenSSL 3's default v3_ca extensions).
new_key private/ca_key.pem 2>/dev/null
openssl req -x509 -new -key private/ca_key.pem -sha256 -days "$days" \
  -subj "/O=cosim/CN=cosim test CA" -out identity_ca.pem
cp identity_ca.pem permissions_ca.pem

# The grants' validity: from yesterday (clock skew between hosts) for --days.
not_before=$(date -u -d "-1 day" +%Y-%m-%dT%H:%M:%S)
not_after=$(date -u -d "+$days days" +%Y-%m-%dT%H:%M:%S)
domain_range="<domains><id_range><min>$dmin</min><max>$dmax</max></id_range></domains>"

cat >"$tmp/governance.xml" <<EOF
<?xml version="1.0" encoding="UTF-8"?>
<dds xmlns:xsi="http://www.w3.org/2001/XMLSchema-instance"
     xsi:noNamespaceSchemaLocation="http://www.omg.org/spec/DDS-SECURITY/20170901/omg_shared_ca_governance.xsd">
  <domain_access_rules>
    <domain_rule>
      $domain_range
      <allow_unauthenticated_participants>false</allow_unauthenticated_participants>
      <enable_join_access_control>true</enable_join_access_control>
      <discovery_protection_kind>ENCRYPT</discovery_protection_kind>
      <liveliness_protection_kind>ENCRYPT</liveliness_protection_kind>
      <rtps_protection_kind>NONE</rtps_protection_kind>
      <topic_access_rules>
        <topic_rule>
          <topic_expression>*</topic_expression>
          <enable_discovery_protection>true</enable_discovery_protection>
          <enable_liveliness_protection>true</enable_liveliness_protection>
          <enable_read_access_control>true</enable_read_access_control>
          <enable_write_access_control>true</enable_write_access_control>
          <metadata_protection_kind>ENCRYPT</metadata_protection_kind>
          <data_protection_kind>ENCRYPT</data_protection_kind>
        </topic_rule>
      </topic_access_rules>
    </domain_rule>
  </domain_access_rules>
</dds>
EOF
sign() { openssl smime -sign -in "$1" -text -out "$2" -signer permissions_ca.pem -inkey private/ca_key.pem; }
sign "$tmp/governance.xml" governance.p7s

for role in tyre terrain coupler monitor; do
  mkdir -p "$role"
  new_key "$role/key.pem" 2>/dev/null
  openssl req -new -key "$role/key.pem" -subj "/O=cosim/CN=cosim-$role" -out "$tmp/$role.csr"
  openssl x509 -req -in "$tmp/$role.csr" -CA identity_ca.pem -CAkey private/ca_key.pem -CAcreateserial \
    -CAserial "$tmp/ca.srl" -days "$days" -sha256 -out "$role/cert.pem" 2>/dev/null
  # The subject as the certificate states it (RFC 2253 order), which is what
  # both vendors compare the grant's subject_name with.
  subject=$(openssl x509 -in "$role/cert.pem" -noout -subject -nameopt RFC2253 | sed 's/^subject=//')
  publish="<publish><topics><topic>*</topic></topics></publish>"
  [[ $role == monitor ]] && publish=""
  cat >"$tmp/permissions_$role.xml" <<EOF
<?xml version="1.0" encoding="UTF-8"?>
<dds xmlns:xsi="http://www.w3.org/2001/XMLSchema-instance"
     xsi:noNamespaceSchemaLocation="http://www.omg.org/spec/DDS-SECURITY/20170901/omg_shared_ca_permissions.xsd">
  <permissions>
    <grant name="cosim_${role}">
      <subject_name>$subject</subject_name>
      <validity><not_before>$not_before</not_before><not_after>$not_after</not_after></validity>
      <allow_rule>
        $domain_range
        $publish
        <subscribe><topics><topic>*</topic></topics></subscribe>
      </allow_rule>
      <default>DENY</default>
    </grant>
  </permissions>
</dds>
EOF
  sign "$tmp/permissions_$role.xml" "$role/permissions.p7s"
done
chmod 600 private/ca_key.pem ./*/key.pem
echo "make_test_ca: CA and identities for tyre, terrain, coupler, monitor in $(pwd) (domains $dmin-$dmax)"
