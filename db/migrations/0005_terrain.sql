-- The ground the buildings stand on, as the triangles of the model's terrain
-- (CityJSON TINRelief), each a closed ring of three vertices. The backbone
-- takes the ground level under a robot from them; a 2D index serves the tile
-- query's square of the ground. A source's triangles are replaced with it.
CREATE TABLE terrain_triangle (
  id      bigserial PRIMARY KEY,
  site_id integer NOT NULL REFERENCES site (id) ON DELETE CASCADE,
  source  text NOT NULL,
  geom    geometry(PolygonZ) NOT NULL CHECK (ST_NPoints(geom) = 4)
);
CREATE INDEX terrain_triangle_geom_2d ON terrain_triangle USING gist (geom);
CREATE INDEX terrain_triangle_source ON terrain_triangle (site_id, source);
ALTER TABLE source_file ADD COLUMN terrain_triangles integer NOT NULL DEFAULT 0;
