#include "scene.h"

#include <math.h>
#include <string.h>

scene_item_t *scene_find(scene_t *s, const char *id)
{
    for (int i = 0; i < s->n; i++)
        if (!strcmp(s->item[i].id, id))
            return &s->item[i];
    return NULL;
}

bool scene_add(scene_t *s, const scene_item_t *item)
{
    if (s->n == SCENE_MAX_ITEMS)
        return false;
    s->item[s->n++] = *item;
    return true;
}

void scene_remove(scene_t *s, scene_item_t *item)
{
    int i = (int)(item - s->item);
    memmove(&s->item[i], &s->item[i + 1], (size_t)(s->n - i - 1) * sizeof s->item[0]);
    s->n--;
}

void scene_step(scene_t *s, double dt)
{
    for (int i = 0; i < s->n; i++) {
        s->item[i].x += s->item[i].vx * dt;
        s->item[i].y += s->item[i].vy * dt;
    }
}

bool scene_overlaps(const scene_t *s, double x, double y, double radius)
{
    for (int i = 0; i < s->n; i++) {
        double dx = s->item[i].x - x, dy = s->item[i].y - y, reach = radius + s->item[i].radius;
        if (dx * dx + dy * dy < reach * reach)
            return true;
    }
    return false;
}

bool scene_blocks(const scene_t *s, double x0, double y0, double x1, double y1, double radius)
{
    for (int i = 0; i < s->n; i++) {
        const scene_item_t *it = &s->item[i];
        double dx = it->x - x1, dy = it->y - y1, reach = radius + it->radius;
        double now_dx = it->x - x0, now_dy = it->y - y0;
        if (dx * dx + dy * dy < reach * reach && dx * dx + dy * dy < now_dx * now_dx + now_dy * now_dy)
            return true;
    }
    return false;
}

double scene_raycast(const scene_t *s, double x, double y, double angle, double max_range)
{
    double best = max_range, ux = cos(angle), uy = sin(angle);
    for (int i = 0; i < s->n; i++) {
        double ox = s->item[i].x - x, oy = s->item[i].y - y, rr = s->item[i].radius;
        double along = ox * ux + oy * uy;
        double perp2 = ox * ox + oy * oy - along * along;
        if (along <= 0 || perp2 > rr * rr)
            continue;
        double t = along - sqrt(rr * rr - perp2);
        if (t >= 0 && t < best)
            best = t;
    }
    return best;
}
