-- The first lineloc schema: sites, buildings, their faces and their 3D lines.
--
-- Geometry is stored in the site's projected CRS (full coordinates, SRID of the
-- site); programs subtract the site origin so the numbers they handle stay small.

CREATE EXTENSION IF NOT EXISTS postgis;

CREATE TABLE site (
  id        serial PRIMARY KEY,
  name      text NOT NULL UNIQUE,
  srid      integer NOT NULL CHECK (srid > 0),
  origin_x  double precision NOT NULL,
  origin_y  double precision NOT NULL,
  origin_z  double precision NOT NULL DEFAULT 0
);

CREATE TABLE building (
  id          bigserial PRIMARY KEY,
  site_id     integer NOT NULL REFERENCES site (id) ON DELETE CASCADE,
  source      text NOT NULL,          -- the file or service it came from
  source_id   text NOT NULL,          -- its object id there
  source_hash text,                   -- hash of the source file at load time
  attributes  jsonb NOT NULL DEFAULT '{}'::jsonb,
  loaded_at   timestamptz NOT NULL DEFAULT now(),
  UNIQUE (site_id, source, source_id)
);

-- Surface kinds follow CityJSON semantics.
CREATE TABLE face_kind (
  code smallint PRIMARY KEY,
  name text NOT NULL UNIQUE
);
INSERT INTO face_kind (code, name) VALUES
  (0, 'other'), (1, 'wall'), (2, 'roof'), (3, 'ground');

CREATE TABLE face (
  id          bigserial PRIMARY KEY,
  site_id     integer NOT NULL REFERENCES site (id) ON DELETE CASCADE,
  building_id bigint NOT NULL REFERENCES building (id) ON DELETE CASCADE,
  kind        smallint NOT NULL DEFAULT 0 REFERENCES face_kind (code),
  geom        geometry(PolygonZ) NOT NULL
);

-- What a line is, for the matcher: which edges can show against the sky, which
-- are vertical, which touch the ground.
CREATE TABLE line_kind (
  code smallint PRIMARY KEY,
  name text NOT NULL UNIQUE
);
INSERT INTO line_kind (code, name) VALUES
  (0, 'other'), (1, 'vertical'), (2, 'eave'), (3, 'ridge'), (4, 'ground');

-- Where a line came from: the city model, or seen by robots and added later.
CREATE TABLE line_provenance (
  code smallint PRIMARY KEY,
  name text NOT NULL UNIQUE
);
INSERT INTO line_provenance (code, name) VALUES (0, 'model'), (1, 'observed');

CREATE TABLE line (
  id          bigserial PRIMARY KEY,
  site_id     integer NOT NULL REFERENCES site (id) ON DELETE CASCADE,
  building_id bigint NOT NULL REFERENCES building (id) ON DELETE CASCADE,
  kind        smallint NOT NULL DEFAULT 0 REFERENCES line_kind (code),
  provenance  smallint NOT NULL DEFAULT 0 REFERENCES line_provenance (code),
  geom        geometry(LineStringZ) NOT NULL CHECK (ST_NPoints(geom) = 2)
);

-- n-D GiST indexes: the 3D box operator &&& and ST_3DDWithin use them.
CREATE INDEX line_geom_nd ON line USING gist (geom gist_geometry_ops_nd);
CREATE INDEX face_geom_nd ON face USING gist (geom gist_geometry_ops_nd);
CREATE INDEX line_building ON line (building_id);
CREATE INDEX face_building ON face (building_id);
