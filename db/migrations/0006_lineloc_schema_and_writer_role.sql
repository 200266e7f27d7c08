-- lineloc's tables in a schema of their own, lineloc, instead of public, and
-- what each of lineloc's roles may do with them (docs/production.md): the
-- owner, who runs these migrations, owns them; the writer (lineloc-load)
-- reads, inserts, updates and deletes rows and changes no table; the reader
-- (lineloc-backbone) reads. The roles are the cluster's (deploy/pg.sh makes
-- them); this migration grants to them. Every session in the database finds
-- the tables, and PostGIS in public, by the database's search_path.
CREATE SCHEMA lineloc;

-- The functions first: line_pack_record's signature names public.line.
ALTER FUNCTION public.line_pack_record(public.line) SET SCHEMA lineloc;
ALTER FUNCTION public.refresh_line_packs(bigint[]) SET SCHEMA lineloc;
ALTER FUNCTION public.refresh_line_packs_after_change() SET SCHEMA lineloc;
ALTER VIEW public.line_pack_of_building SET SCHEMA lineloc;
-- Indexes, constraints, triggers and the id sequences move with their tables.
ALTER TABLE public.schema_migrations SET SCHEMA lineloc;
ALTER TABLE public.site SET SCHEMA lineloc;
ALTER TABLE public.building SET SCHEMA lineloc;
ALTER TABLE public.face_kind SET SCHEMA lineloc;
ALTER TABLE public.face SET SCHEMA lineloc;
ALTER TABLE public.line_kind SET SCHEMA lineloc;
ALTER TABLE public.line_provenance SET SCHEMA lineloc;
ALTER TABLE public.line SET SCHEMA lineloc;
ALTER TABLE public.source_file SET SCHEMA lineloc;
ALTER TABLE public.building_line_pack SET SCHEMA lineloc;
ALTER TABLE public.terrain_triangle SET SCHEMA lineloc;

DO $$
BEGIN
  EXECUTE format('ALTER DATABASE %I SET search_path = lineloc, public', current_database());
END
$$;
-- This session too, for the migrations after this one.
SET search_path = lineloc, public;

GRANT USAGE ON SCHEMA lineloc TO lineloc_writer, lineloc_reader;
GRANT SELECT ON ALL TABLES IN SCHEMA lineloc TO lineloc_reader;
GRANT SELECT, INSERT, UPDATE, DELETE ON ALL TABLES IN SCHEMA lineloc TO lineloc_writer;
GRANT USAGE ON ALL SEQUENCES IN SCHEMA lineloc TO lineloc_writer;
REVOKE INSERT, UPDATE, DELETE ON schema_migrations FROM lineloc_writer;
ALTER DEFAULT PRIVILEGES IN SCHEMA lineloc GRANT SELECT ON TABLES TO lineloc_reader;
ALTER DEFAULT PRIVILEGES IN SCHEMA lineloc
  GRANT SELECT, INSERT, UPDATE, DELETE ON TABLES TO lineloc_writer;
ALTER DEFAULT PRIVILEGES IN SCHEMA lineloc GRANT USAGE ON SEQUENCES TO lineloc_writer;
