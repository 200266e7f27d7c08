-- A pass that should have seen a learnt line and did not: one row per line
-- and pass, so writing a pass again changes nothing. A line missed on enough
-- separate passes since it was last seen is retired (db/enrichment_store.h):
-- the shop sign taken down, the scaffolding gone.
CREATE TABLE enrichment_miss (
  line_id   bigint NOT NULL REFERENCES enrichment_line (id) ON DELETE CASCADE,
  pass      text NOT NULL CHECK (pass <> ''),
  missed_at timestamptz NOT NULL,
  PRIMARY KEY (line_id, pass)
);

REVOKE INSERT, UPDATE, DELETE ON enrichment_miss FROM lineloc_writer;
GRANT INSERT, UPDATE, DELETE ON enrichment_miss TO lineloc_enricher;
