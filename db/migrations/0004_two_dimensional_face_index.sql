-- Indexes for what the queries read. The radius, frustum and tile queries read
-- lines through building_line_pack, so no query reads line geometry through a
-- spatial index, and the tile query's faces need only a 2D box (a column over
-- a square of the ground). An n-D GiST insertion costs several times a 2D one
-- and was the largest part of a load, so the n-D indexes go and faces get a
-- 2D index.
DROP INDEX line_geom_nd;
DROP INDEX face_geom_nd;
CREATE INDEX face_geom_2d ON face USING gist (geom);
