-- Fast loads and fast queries of the lines near the robot (paper §3.1).
--
-- Loads: a foreign key costs one index lookup per inserted row, so kinds and
-- provenance are checked with CHECK constraints (the lookup tables stay, to
-- name the codes), and line.site_id / face.site_id are plain copies of their
-- building's site kept for index filters: the building's foreign key, with its
-- cascade, carries the integrity (deleting a site deletes its buildings, which
-- delete their faces and lines).
ALTER TABLE face
  DROP CONSTRAINT face_kind_fkey,
  DROP CONSTRAINT face_site_id_fkey,
  ADD CONSTRAINT face_kind_check CHECK (kind BETWEEN 0 AND 3);
ALTER TABLE line
  DROP CONSTRAINT line_kind_fkey,
  DROP CONSTRAINT line_provenance_fkey,
  DROP CONSTRAINT line_site_id_fkey,
  ADD CONSTRAINT line_kind_check CHECK (kind BETWEEN 0 AND 4),
  ADD CONSTRAINT line_provenance_check CHECK (provenance BETWEEN 0 AND 1);

-- Queries: building_line_pack holds each building's lines in one row under one
-- 2D box, the access path of the radius and view-frustum queries (one GiST
-- entry and one heap tuple per building instead of one per line). It is
-- derived from table line (public.line: plain "line" names a built-in type in
-- a function signature): line_pack_of_building computes it, and a trigger
-- keeps it in step with every change of line, unless the writing transaction
-- says it writes the packs itself (lineloc.line_packs_written = 'on', as
-- lineloc-load does, with the same bytes).
--
-- One record per line, ordered by id, big-endian, 114 bytes (db/line_pack.h):
--   id int8, kind int2, face_a int4, face_b int4 (-1 when absent),
--   start xyz, end xyz, normal_a xyz, normal_b xyz float8
--   (site CRS coordinates; a normal is zero when its face is absent).
CREATE TABLE building_line_pack (
  building_id bigint PRIMARY KEY REFERENCES building (id) ON DELETE CASCADE,
  site_id     integer NOT NULL,
  bounds      box NOT NULL,  -- x, y extent of the building's lines (site CRS)
  lines       bytea NOT NULL CHECK (length(lines) % 114 = 0)
);
-- Packs stay inline and uncompressed up to a full page: no TOAST fetch and no
-- decompression when a query reads them.
ALTER TABLE building_line_pack ALTER COLUMN lines SET STORAGE EXTERNAL;
ALTER TABLE building_line_pack SET (toast_tuple_target = 8160);
CREATE INDEX building_line_pack_bounds ON building_line_pack USING gist (bounds);

CREATE FUNCTION line_pack_record(l public.line) RETURNS bytea LANGUAGE sql IMMUTABLE AS $$
  SELECT int8send((l).id) || int2send((l).kind)
      || int4send(coalesce((l).face_a, -1)) || int4send(coalesce((l).face_b, -1))
      || float8send(ST_X(ST_StartPoint((l).geom))) || float8send(ST_Y(ST_StartPoint((l).geom)))
      || float8send(ST_Z(ST_StartPoint((l).geom)))
      || float8send(ST_X(ST_EndPoint((l).geom))) || float8send(ST_Y(ST_EndPoint((l).geom)))
      || float8send(ST_Z(ST_EndPoint((l).geom)))
      || float8send(coalesce((l).normal_a_x, 0)) || float8send(coalesce((l).normal_a_y, 0))
      || float8send(coalesce((l).normal_a_z, 0))
      || float8send(coalesce((l).normal_b_x, 0)) || float8send(coalesce((l).normal_b_y, 0))
      || float8send(coalesce((l).normal_b_z, 0))
$$;

CREATE VIEW line_pack_of_building AS
SELECT building_id,
       min(site_id) AS site_id,
       box(point(min(ST_XMin(geom)), min(ST_YMin(geom))),
           point(max(ST_XMax(geom)), max(ST_YMax(geom)))) AS bounds,
       string_agg(line_pack_record(line), ''::bytea ORDER BY id) AS lines
FROM line
GROUP BY building_id;

CREATE FUNCTION refresh_line_packs(building_ids bigint[]) RETURNS void LANGUAGE sql AS $$
  DELETE FROM building_line_pack WHERE building_id = ANY (building_ids);
  INSERT INTO building_line_pack (building_id, site_id, bounds, lines)
  SELECT building_id, site_id, bounds, lines FROM line_pack_of_building
  WHERE building_id = ANY (building_ids);
$$;

CREATE FUNCTION refresh_line_packs_after_change() RETURNS trigger LANGUAGE plpgsql AS $$
BEGIN
  IF current_setting('lineloc.line_packs_written', true) IS NOT DISTINCT FROM 'on' THEN
    RETURN NULL;
  END IF;
  IF TG_OP = 'TRUNCATE' THEN
    TRUNCATE building_line_pack;
  ELSIF TG_OP = 'UPDATE' THEN
    PERFORM refresh_line_packs(ARRAY(SELECT building_id FROM changed_lines
                                     UNION SELECT building_id FROM updated_lines));
  ELSE
    PERFORM refresh_line_packs(ARRAY(SELECT DISTINCT building_id FROM changed_lines));
  END IF;
  RETURN NULL;
END
$$;

CREATE TRIGGER line_packs_after_insert AFTER INSERT ON line
  REFERENCING NEW TABLE AS changed_lines
  FOR EACH STATEMENT EXECUTE FUNCTION refresh_line_packs_after_change();
CREATE TRIGGER line_packs_after_delete AFTER DELETE ON line
  REFERENCING OLD TABLE AS changed_lines
  FOR EACH STATEMENT EXECUTE FUNCTION refresh_line_packs_after_change();
CREATE TRIGGER line_packs_after_update AFTER UPDATE ON line
  REFERENCING OLD TABLE AS changed_lines NEW TABLE AS updated_lines
  FOR EACH STATEMENT EXECUTE FUNCTION refresh_line_packs_after_change();
CREATE TRIGGER line_packs_after_truncate AFTER TRUNCATE ON line
  FOR EACH STATEMENT EXECUTE FUNCTION refresh_line_packs_after_change();

INSERT INTO building_line_pack (building_id, site_id, bounds, lines)
SELECT building_id, site_id, bounds, lines FROM line_pack_of_building;
