-- Lines the robots saw that the model lacks (enrichment, paper §3.1), kept
-- beside the loaded model and never among its lines: a reload of the model
-- leaves them, and a purge of them leaves the model.
--
-- A line is a candidate until sightings from two separate passes (drives or
-- days: a van parked for one pass is no wall) confirm it; it is retired when
-- passes that should have seen it did not. Each pass's sighting is one row of
-- enrichment_sighting, keyed by line, pass and robot, so writing a pass again
-- changes nothing. Geometry is in the site's CRS, as the model's lines; the
-- plane is the model face's it lies on (n . x = offset, site frame: the site's
-- CRS minus its origin), the covariances those of its ends (m^2, row-major
-- 3 x 3, site frame).
--
-- The enricher role (lineloc-enrich, and the backbone while it learns)
-- writes them; the loader's writer may not; the reader reads them.
CREATE TABLE enrichment_status (
  code smallint PRIMARY KEY,
  name text NOT NULL UNIQUE
);
INSERT INTO enrichment_status (code, name) VALUES
  (0, 'candidate'), (1, 'confirmed'), (2, 'retired');

CREATE TABLE enrichment_line (
  id               bigserial PRIMARY KEY,
  site_id          integer NOT NULL REFERENCES site (id) ON DELETE CASCADE,
  -- The building whose face it lies on, where the model came from the database.
  building_id      bigint REFERENCES building (id) ON DELETE SET NULL,
  geom             geometry(LineStringZ) NOT NULL CHECK (ST_NPoints(geom) = 2),
  plane_normal     double precision[] NOT NULL CHECK (array_length(plane_normal, 1) = 3),
  plane_offset     double precision NOT NULL,
  start_covariance double precision[] NOT NULL CHECK (array_length(start_covariance, 1) = 9),
  end_covariance   double precision[] NOT NULL CHECK (array_length(end_covariance, 1) = 9),
  status           smallint NOT NULL DEFAULT 0 REFERENCES enrichment_status (code),
  first_seen       timestamptz NOT NULL,
  last_seen        timestamptz NOT NULL CHECK (last_seen >= first_seen)
);
CREATE INDEX enrichment_line_geom_nd ON enrichment_line USING gist (geom gist_geometry_ops_nd);
CREATE INDEX enrichment_line_site ON enrichment_line (site_id, status);

CREATE TABLE enrichment_sighting (
  line_id    bigint NOT NULL REFERENCES enrichment_line (id) ON DELETE CASCADE,
  pass       text NOT NULL CHECK (pass <> ''),
  robot      text NOT NULL CHECK (robot <> ''),
  views      integer NOT NULL CHECK (views > 0),
  first_seen timestamptz NOT NULL,
  last_seen  timestamptz NOT NULL CHECK (last_seen >= first_seen),
  PRIMARY KEY (line_id, pass, robot)
);
CREATE INDEX enrichment_sighting_pass ON enrichment_sighting (pass);

REVOKE INSERT, UPDATE, DELETE ON enrichment_status, enrichment_line, enrichment_sighting
  FROM lineloc_writer;
GRANT USAGE ON SCHEMA lineloc TO lineloc_enricher;
GRANT SELECT ON ALL TABLES IN SCHEMA lineloc TO lineloc_enricher;
GRANT INSERT, UPDATE, DELETE ON enrichment_line, enrichment_sighting TO lineloc_enricher;
GRANT USAGE ON SEQUENCE enrichment_line_id_seq TO lineloc_enricher;
ALTER DEFAULT PRIVILEGES IN SCHEMA lineloc GRANT SELECT ON TABLES TO lineloc_enricher;
