-- A single 10 m cube standing at the origin of site 'demo' (RD New, EPSG:7415),
-- with its 6 faces and 12 edges: the smallest model the loop can run on before
-- lineloc-load fills a database from real city models.
BEGIN;
INSERT INTO site (name, srid, origin_x, origin_y, origin_z)
VALUES ('demo', 7415, 85000, 447000, 0)
ON CONFLICT (name) DO NOTHING;

DELETE FROM building WHERE source = 'deploy/demo/box_building.sql';

WITH s AS (SELECT id, srid, origin_x AS ox, origin_y AS oy FROM site WHERE name = 'demo'),
b AS (
  INSERT INTO building (site_id, source, source_id, attributes)
  SELECT id, 'deploy/demo/box_building.sql', 'cube-1', '{"height_m": 10}' FROM s
  RETURNING id, site_id
),
corner (name, x, y, z) AS (VALUES
  ('a', 0, 0, 0), ('b', 10, 0, 0), ('c', 10, 10, 0), ('d', 0, 10, 0),
  ('e', 0, 0, 10), ('f', 10, 0, 10), ('g', 10, 10, 10), ('h', 0, 10, 10)),
edge (p, q, kind) AS (VALUES
  ('a', 'b', 4), ('b', 'c', 4), ('c', 'd', 4), ('d', 'a', 4),
  ('e', 'f', 2), ('f', 'g', 2), ('g', 'h', 2), ('h', 'e', 2),
  ('a', 'e', 1), ('b', 'f', 1), ('c', 'g', 1), ('d', 'h', 1)),
lines AS (
  INSERT INTO line (site_id, building_id, kind, geom)
  SELECT b.site_id, b.id, edge.kind,
         ST_SetSRID(ST_MakeLine(ST_MakePoint(s.ox + p.x, s.oy + p.y, p.z),
                                ST_MakePoint(s.ox + q.x, s.oy + q.y, q.z)), s.srid)
  FROM edge JOIN corner p ON p.name = edge.p JOIN corner q ON q.name = edge.q, b, s
  RETURNING 1
),
face_ring (kind, ring) AS (VALUES
  (3, ARRAY['a', 'd', 'c', 'b', 'a']), (2, ARRAY['e', 'f', 'g', 'h', 'e']),
  (1, ARRAY['a', 'b', 'f', 'e', 'a']), (1, ARRAY['b', 'c', 'g', 'f', 'b']),
  (1, ARRAY['c', 'd', 'h', 'g', 'c']), (1, ARRAY['d', 'a', 'e', 'h', 'd']))
INSERT INTO face (site_id, building_id, kind, geom)
SELECT b.site_id, b.id, face_ring.kind,
       ST_SetSRID(ST_MakePolygon(ST_MakeLine(ARRAY(
         SELECT ST_MakePoint(s.ox + c.x, s.oy + c.y, c.z)
         FROM unnest(face_ring.ring) WITH ORDINALITY AS r (name, i)
         JOIN corner c ON c.name = r.name ORDER BY r.i))), s.srid)
FROM face_ring, b, s;
COMMIT;
