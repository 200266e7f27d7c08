#!/usr/bin/env bash
# The site's DDS Security (OMG DDS Security 1.1) material for Cyclone DDS's
# plugins: one certificate authority that signs every participant's identity
# certificate, the domain governance and each participant's permissions; a
# certificate revocation list; and, per participant, a Cyclone DDS XML overlay
# that a program adds to its --dds-config.
#
#   deploy/dds-security.sh init                create the CA and the signed governance; idempotent
#   deploy/dds-security.sh issue robot ID      identity and permissions of robot ID; prints its overlay
#   deploy/dds-security.sh issue backbone NAME identity and permissions of a backbone; prints its overlay
#   deploy/dds-security.sh revoke PARTICIPANT  revoke robot-ID or backbone-NAME (CRL)
#   deploy/dds-security.sh config PARTICIPANT  print the overlay of an issued participant
#
# Governance: no unauthenticated participant joins; discovery, liveliness and
# every lineloc topic's payload are encrypted (AES-GCM). Permissions: robot ID
# publishes LineSet, Exposure and RobotState, and subscribes PoseFix, only in
# partition "robot.ID"; a backbone subscribes those three and publishes PoseFix
# in every "robot.*" partition. Nothing else is granted. Both documents cover
# DDS domains 0-230, all that DDS Security's documents name.
#
# Environment: LINELOC_DDS_SECURITY_DIR (where it all lives, default
# out/dds-security/; the CA's key is in ca/, mode 0700), LINELOC_DDS_SECURITY_DAYS
# (validity of certificates and permissions, default 365).
set -euo pipefail
ROOT="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
DIR="${LINELOC_DDS_SECURITY_DIR:-$ROOT/out/dds-security}"
DAYS="${LINELOC_DDS_SECURITY_DAYS:-365}"
CA_DIR="$DIR/ca"
PLUGIN_DIR="$(dirname "$(find /usr/lib /usr/local/lib -name 'libdds_security_auth.so' -print -quit 2>/dev/null || true)")"
ORGANISATION="lineloc"

die() { echo "dds-security.sh: $*" >&2; exit 1; }
command -v openssl >/dev/null || die "openssl not found; run deploy/install-deps.sh"

# Writes stdin to $1 atomically, never through a symlink.
write_file() {
  local target="$1" tmp
  tmp="$(mktemp "$(dirname "$target")/.tmp.XXXXXX")"
  cat >"$tmp"
  mv -f "$tmp" "$target"
}

private_dir() {
  [ ! -L "$1" ] || die "$1 is a symbolic link; refusing to use it"
  mkdir -p -m 700 "$1"
  [ -O "$1" ] || die "$1 is not owned by $(id -un); refusing to use it"
}

ca_config() {
  cat <<CONF
[ ca ]
default_ca = site_ca
[ site_ca ]
dir = $CA_DIR
database = \$dir/index.txt
serial = \$dir/serial
crlnumber = \$dir/crlnumber
new_certs_dir = \$dir/issued
certificate = \$dir/ca.pem
private_key = \$dir/ca.key
default_md = sha256
default_days = $DAYS
default_crl_days = $DAYS
policy = any_name
unique_subject = no
copy_extensions = none
[ any_name ]
commonName = supplied
organizationName = supplied
[ req ]
distinguished_name = req_name
prompt = no
[ req_name ]
CONF
}

openssl_ca() {
  ca_config >"$CA_DIR/openssl.cnf"
  openssl ca -batch -config "$CA_DIR/openssl.cnf" "$@" 2>"$CA_DIR/openssl.log" ||
    { cat "$CA_DIR/openssl.log" >&2; die "openssl ca $1 failed"; }
}

domains_xml() {
  echo "<domains><id_range><min>0</min><max>230</max></id_range></domains>"
}

governance_xml() {
  cat <<XML
<?xml version="1.0" encoding="UTF-8"?>
<dds xmlns:xsi="http://www.w3.org/2001/XMLSchema-instance"
     xsi:noNamespaceSchemaLocation="http://www.omg.org/spec/DDS-SECURITY/20170901/omg_shared_ca_governance.xsd">
  <domain_access_rules>
    <domain_rule>
      $(domains_xml)
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
XML
}

# $1: topics (blank-separated), $2: partition pattern.
topics_in_partition_xml() {
  echo "<topics>"
  for topic in $1; do echo "<topic>$topic</topic>"; done
  echo "</topics><partitions><partition>$2</partition></partitions>"
}

# $1: participant, $2: what it publishes, $3: what it subscribes, $4: partition pattern,
# $5: topics it publishes and subscribes in the backbones' partition (none for a robot).
permissions_xml() {
  local not_before not_after
  not_before="$(date -u +%Y-%m-%dT%H:%M:%S)"
  not_after="$(date -u -d "+$DAYS days" +%Y-%m-%dT%H:%M:%S)"
  cat <<XML
<?xml version="1.0" encoding="UTF-8"?>
<dds xmlns:xsi="http://www.w3.org/2001/XMLSchema-instance"
     xsi:noNamespaceSchemaLocation="http://www.omg.org/spec/DDS-SECURITY/20170901/omg_shared_ca_permissions.xsd">
  <permissions>
    <grant name="$1">
      <subject_name>$(subject "$1")</subject_name>
      <validity><not_before>$not_before</not_before><not_after>$not_after</not_after></validity>
      <allow_rule>
        $(domains_xml)
        <publish>$(topics_in_partition_xml "$2" "$4")</publish>
        <subscribe>$(topics_in_partition_xml "$3" "$4")</subscribe>
        $(if [ -n "${5:-}" ]; then
          echo "<publish>$(topics_in_partition_xml "$5" lineloc.backbones)</publish>"
          echo "<subscribe>$(topics_in_partition_xml "$5" lineloc.backbones)</subscribe>"
        fi)
      </allow_rule>
      <default>DENY</default>
    </grant>
  </permissions>
</dds>
XML
}

subject() { echo "CN=$1,O=$ORGANISATION"; }

sign() {
  openssl smime -sign -text -in "$1" -out "$2" -signer "$CA_DIR/ca.pem" -inkey "$CA_DIR/ca.key" ||
    die "signing $1 failed"
}

overlay_xml() {
  local identity="$1"
  cat <<XML
<?xml version="1.0" encoding="UTF-8"?>
<CycloneDDS xmlns="https://cdds.io/config">
  <Domain id="any">
    <Security>
      <Authentication>
        <Library path="$PLUGIN_DIR/libdds_security_auth.so" initFunction="init_authentication" finalizeFunction="finalize_authentication"/>
        <IdentityCertificate>file:$identity/cert.pem</IdentityCertificate>
        <IdentityCA>file:$CA_DIR/ca.pem</IdentityCA>
        <PrivateKey>file:$identity/key.pem</PrivateKey>
        <CRL>file:$CA_DIR/crl.pem</CRL>
      </Authentication>
      <Cryptographic>
        <Library path="$PLUGIN_DIR/libdds_security_crypto.so" initFunction="init_crypto" finalizeFunction="finalize_crypto"/>
      </Cryptographic>
      <AccessControl>
        <Library path="$PLUGIN_DIR/libdds_security_ac.so" initFunction="init_access_control" finalizeFunction="finalize_access_control"/>
        <Governance>file:$DIR/governance.p7s</Governance>
        <PermissionsCA>file:$CA_DIR/ca.pem</PermissionsCA>
        <Permissions>file:$identity/permissions.p7s</Permissions>
      </AccessControl>
    </Security>
  </Domain>
</CycloneDDS>
XML
}

init() {
  [ -f "$PLUGIN_DIR/libdds_security_auth.so" ] ||
    die "Cyclone DDS's security plugins not found; run deploy/install-deps.sh"
  private_dir "$DIR"
  private_dir "$CA_DIR"
  if [ ! -f "$CA_DIR/ca.pem" ]; then
    mkdir -p -m 700 "$CA_DIR/issued"
    : >"$CA_DIR/index.txt"
    echo 1000 >"$CA_DIR/serial"
    echo 1000 >"$CA_DIR/crlnumber"
    (umask 077 && openssl ecparam -name prime256v1 -genkey -noout -out "$CA_DIR/ca.key")
    openssl req -x509 -new -key "$CA_DIR/ca.key" -sha256 -days $((DAYS * 10)) \
      -subj "/CN=lineloc site CA/O=$ORGANISATION" -out "$CA_DIR/ca.pem"
    openssl_ca -gencrl -out "$CA_DIR/crl.pem"
  fi
  if [ ! -f "$DIR/governance.p7s" ]; then
    governance_xml | write_file "$DIR/governance.xml"
    sign "$DIR/governance.xml" "$DIR/governance.p7s"
  fi
}

issue() {
  local kind="$1" name="$2" participant publish subscribe partition peers=""
  [[ "$name" =~ ^[A-Za-z0-9][A-Za-z0-9_.-]*$ ]] || die "$kind name '$name' must match [A-Za-z0-9][A-Za-z0-9_.-]*"
  case "$kind" in
    robot)
      publish="lineloc_LineSet lineloc_Exposure lineloc_RobotState"
      subscribe="lineloc_PoseFix"
      partition="robot.$name"
      ;;
    backbone)
      publish="lineloc_PoseFix"
      subscribe="lineloc_LineSet lineloc_Exposure lineloc_RobotState"
      partition="robot.*"
      peers="lineloc_Backbone lineloc_TrackingHandover"
      ;;
    *) die "issue: unknown participant kind '$kind' (robot or backbone)" ;;
  esac
  init
  participant="$kind-$name"
  local identity="$DIR/identities/$participant"
  private_dir "$DIR/identities"
  private_dir "$identity"
  (umask 077 && openssl ecparam -name prime256v1 -genkey -noout -out "$identity/key.pem")
  openssl req -new -key "$identity/key.pem" -subj "/CN=$participant/O=$ORGANISATION" \
    -out "$identity/request.pem"
  openssl_ca -notext -in "$identity/request.pem" -out "$identity/cert.pem" \
    -subj "/CN=$participant/O=$ORGANISATION"
  permissions_xml "$participant" "$publish" "$subscribe" "$partition" "$peers" |
    write_file "$identity/permissions.xml"
  sign "$identity/permissions.xml" "$identity/permissions.p7s"
  overlay_xml "$identity" | write_file "$identity/cyclonedds-security.xml"
  echo "$identity/cyclonedds-security.xml"
}

revoke() {
  local identity="$DIR/identities/$1"
  [ -f "$identity/cert.pem" ] || die "no participant '$1' issued in $DIR"
  openssl_ca -revoke "$identity/cert.pem"
  openssl_ca -gencrl -out "$CA_DIR/crl.pem"
  echo "revoked $1; participants read the CRL when they start"
}

config() {
  local overlay="$DIR/identities/$1/cyclonedds-security.xml"
  [ -f "$overlay" ] || die "no participant '$1' issued in $DIR (deploy/dds-security.sh issue ...)"
  echo "$overlay"
}

case "${1:-}" in
  init) init ;;
  issue) [ $# -eq 3 ] || die "usage: issue robot|backbone NAME"; issue "$2" "$3" ;;
  revoke) [ $# -eq 2 ] || die "usage: revoke PARTICIPANT"; revoke "$2" ;;
  config) [ $# -eq 2 ] || die "usage: config PARTICIPANT"; config "$2" ;;
  *) die "usage: $0 init|issue|revoke|config (see the header of this script)" ;;
esac
