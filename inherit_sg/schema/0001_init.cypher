// INHerit-SG map schema, version 1.
// Placeholders {visual_dim}, {text_dim} and {image_feature_dim} are filled from map.json.
// Every statement must be idempotent (IF NOT EXISTS; index calls are skipped when the
// index exists) so that a migration interrupted half-way can simply run again.

// ---- the four scene-graph layers -----------------------------------------------------
CREATE NODE TABLE IF NOT EXISTS Floor(
    id STRING PRIMARY KEY, label STRING, level INT64, z_min DOUBLE, z_max DOUBLE);

CREATE NODE TABLE IF NOT EXISTS Room(
    id STRING PRIMARY KEY, label STRING, floor_id STRING, position DOUBLE[3],
    summary STRING, mask BLOB, best_view STRING);

CREATE NODE TABLE IF NOT EXISTS Area(
    id STRING PRIMARY KEY, label STRING, room_id STRING, position DOUBLE[3], summary STRING);

CREATE NODE TABLE IF NOT EXISTS Object(
    id STRING PRIMARY KEY, label STRING, position DOUBLE[3],
    bbox_min DOUBLE[3], bbox_max DOUBLE[3], description STRING, status STRING,
    observation_count INT64, first_seen DOUBLE, last_seen DOUBLE,
    keyframe_ids STRING[], best_keyframe STRING, attributes STRING,
    floor_id STRING, room_id STRING, area_id STRING);

// ---- capture history -------------------------------------------------------------------
CREATE NODE TABLE IF NOT EXISTS Keyframe(
    id STRING PRIMARY KEY, label STRING, session_id STRING, timestamp DOUBLE,
    frame_index INT64, floor_id STRING, pose DOUBLE[16], width INT64, height INT64);

CREATE NODE TABLE IF NOT EXISTS Session(
    id STRING PRIMARY KEY, label STRING, name STRING, started DOUBLE, finished DOUBLE,
    dataset STRING, frames INT64, keyframes INT64);

// ---- embeddings: own tables, one row per owning node, replaced by delete + insert ------
// (an HNSW-indexed column cannot be SET in Kuzu); digest: hash of the vector's bytes, so
// a writer can tell an unchanged vector without reading it back (slow by id in Kuzu)
CREATE NODE TABLE IF NOT EXISTS ObjectVisual(
    id STRING PRIMARY KEY, vec FLOAT[{visual_dim}], digest STRING);
CREATE NODE TABLE IF NOT EXISTS ObjectText(
    id STRING PRIMARY KEY, vec FLOAT[{text_dim}], digest STRING);
CREATE NODE TABLE IF NOT EXISTS AreaText(
    id STRING PRIMARY KEY, vec FLOAT[{text_dim}], digest STRING);
CREATE NODE TABLE IF NOT EXISTS RoomText(
    id STRING PRIMARY KEY, vec FLOAT[{text_dim}], digest STRING);

// ---- edges (props: JSON of any further edge properties) --------------------------------
CREATE REL TABLE IF NOT EXISTS HAS_ROOM(FROM Floor TO Room, props STRING);
CREATE REL TABLE IF NOT EXISTS HAS_AREA(FROM Room TO Area, props STRING);
CREATE REL TABLE IF NOT EXISTS HAS_OBJECT(FROM Area TO Object, props STRING);
CREATE REL TABLE IF NOT EXISTS CONNECTS(FROM Room TO Room, door DOUBLE[3], props STRING);
CREATE REL TABLE IF NOT EXISTS STAIRS(FROM Floor TO Floor, props STRING);
CREATE REL TABLE IF NOT EXISTS RELATION(
    FROM Object TO Object, predicate STRING, confidence DOUBLE, props STRING);
CREATE REL TABLE IF NOT EXISTS SEEN_IN(FROM Object TO Keyframe, props STRING);

// ---- bookkeeping for the search index (index.kuzu) -------------------------------------
// This database holds no index at all: with any index present, Kuzu 0.11.3 corrupts
// list columns (position, bbox) at checkpoint when rows were updated and appended in
// the same checkpoint interval. HNSW and full-text indexes live in index.kuzu, a mirror
// that the store keeps in step (inherit_sg/store/search_index.py).
CREATE NODE TABLE IF NOT EXISTS _State(name STRING PRIMARY KEY, value INT64);
CREATE NODE TABLE IF NOT EXISTS _TextIndexState(name STRING PRIMARY KEY, dirty BOOLEAN);
