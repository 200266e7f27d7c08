-- What lineloc-load records: each building's place among its source's objects
-- (BuildingPart -> Building), the faces each line lies between with their
-- outward normals, one row per loaded source file, and the read-only role the
-- backbone connects with.

ALTER TABLE building
  ADD COLUMN parent_id   bigint REFERENCES building (id) ON DELETE CASCADE,
  ADD COLUMN object_type text NOT NULL DEFAULT 'Building',
  ADD COLUMN lod         text;              -- level of detail its faces come from
CREATE INDEX building_parent ON building (parent_id);
CREATE INDEX building_source ON building (site_id, source);

-- ordinal: the face's index among its building's faces; normal: outward unit normal.
ALTER TABLE face
  ADD COLUMN ordinal  integer,
  ADD COLUMN normal_x double precision,
  ADD COLUMN normal_y double precision,
  ADD COLUMN normal_z double precision;

-- face_a, face_b: ordinals of the faces the line lies between (face_b NULL on a
-- free border), with their outward unit normals.
ALTER TABLE line
  ADD COLUMN face_a     integer,
  ADD COLUMN face_b     integer,
  ADD COLUMN normal_a_x double precision,
  ADD COLUMN normal_a_y double precision,
  ADD COLUMN normal_a_z double precision,
  ADD COLUMN normal_b_x double precision,
  ADD COLUMN normal_b_y double precision,
  ADD COLUMN normal_b_z double precision;

-- One row per file loaded into a site: loading the same file (same hash, same
-- options) again changes nothing; a changed file replaces its buildings.
CREATE TABLE source_file (
  site_id   integer NOT NULL REFERENCES site (id) ON DELETE CASCADE,
  name      text NOT NULL,
  hash      text NOT NULL,            -- SHA-256 of the file, hex
  options   text NOT NULL DEFAULT '', -- the load options that shape the stored model
  buildings integer NOT NULL,
  faces     integer NOT NULL,
  lines     integer NOT NULL,
  loaded_at timestamptz NOT NULL DEFAULT now(),
  PRIMARY KEY (site_id, name)
);

-- The backbone reads and never writes. Roles are cluster-wide, so creating it
-- must tolerate another database of the cluster having done so already (also
-- concurrently: the catalogue's unique index then reports the race).
DO $$
BEGIN
  IF NOT EXISTS (SELECT FROM pg_roles WHERE rolname = 'lineloc_reader') THEN
    CREATE ROLE lineloc_reader LOGIN;
  END IF;
EXCEPTION WHEN duplicate_object OR unique_violation THEN
  NULL;
END
$$;
GRANT USAGE ON SCHEMA public TO lineloc_reader;
GRANT SELECT ON ALL TABLES IN SCHEMA public TO lineloc_reader;
ALTER DEFAULT PRIVILEGES IN SCHEMA public GRANT SELECT ON TABLES TO lineloc_reader;
